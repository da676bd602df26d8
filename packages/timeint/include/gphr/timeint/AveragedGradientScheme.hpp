#pragma once
/// @file
/// The one implicit time scheme of GPHR, written once for the full (Tpetra), reduced and
/// hyper-reduced (small dense) systems:
///
///   y1 = y0 + dt J  sum_q w_q grad H(y0 + s_q (y1 - y0))                            (*)
///
/// With the 1-point Gauss rule (s = 1/2, w = 1) (*) is the implicit midpoint rule (IMR); with a
/// Gauss-Legendre rule exact for the degree of grad H along the segment, (*) is the Average
/// Vector Field method (AVF), which conserves H exactly when (*) is solved exactly:
/// H(y1) - H(y0) = (y1 - y0)^T gbar = gbar^T R for the Newton residual R, so |dH| <= |gbar| |R|.
///
/// (*) is solved by Newton's method with the exact Jacobian
///   K = I - dt J Hbar,  Hbar = sum_q w_q s_q Hess H(y_q),   K dx = -R.
/// K is assembled with J already applied to the rows of Hbar (a signed row permutation), which
/// keeps its unit diagonal in front: the equivalent J^T K = J^T - dt Hbar has a small diagonal and
/// made ILU preconditioners useless (157 GMRES iterations per Newton step at n = 256).
///
/// Backend concept (see FullModelBackend and, for reduced systems, DenseBackend):
///   using Vector;  Vector create() const;
///   void gradient(const Vector& y, Vector& g);           // g = grad H(y)
///   bool averagedGradient(const Vector& y0, const Vector& y1, const QuadratureRule& rule, Vector& gbar);
///                         // gbar of (*) computed by the model at once; false: the scheme loops over nodes
///   void applyJ(const Vector& x, Vector& out);
///   void beginNewtonMatrix();                            // M = I
///   void addHessian(const Vector& y, double scale);     // M += scale J Hess H(y)
///   bool addAveragedHessian(const Vector& y0, const Vector& y1, const QuadratureRule& rule, double scale);
///                         // M += scale J sum_q w_q s_q Hess H(y_q) at once; false: the scheme loops over nodes
///   void endNewtonMatrix();
///   int solveNewton(const Vector& rhs, Vector& dx, double newtonRelative);
///                         // M dx = rhs; returns linear iterations. newtonRelative = newton tolerance / ||rhs||:
///                         // an iterative solve may stop at a fraction of it (inexact Newton)
///   static void update(Vector& y, double a, const Vector& x, double b);  // y = a x + b y
///   static void update(Vector& y, double a, const Vector& x, double b, const Vector& z, double c);
///   static double norm(const Vector& x);  static void assign(Vector& y, const Vector& x);
#include <Teuchos_ParameterList.hpp>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "gphr/core/Error.hpp"
#include "gphr/core/Quadrature.hpp"

namespace gphr {

/// What one time step's Newton solve took: iterations, Newton matrices and the final residual.
struct StepReport {
  int newtonIterations = 0;  ///< Newton iterations of the step.
  int linearIterations = 0;  ///< Linear (Krylov) iterations over the step's Newton iterations.
  int newtonMatrices = 0;     ///< Newton matrices assembled (and factored / preconditioned) in the step
  double residualNorm = 0.0;  ///< ||R(y1)|| at acceptance
  /// ||gbar|| at acceptance: H(y1) - H(y0) = gbar^T R for AVF's exact rule (a discrete gradient,
  /// gbar^T (y1 - y0) = H(y1) - H(y0), and y1 - y0 = dt J gbar + R with gbar^T J gbar = 0), so
  /// |H(y1) - H(y0)| <= gradientNorm residualNorm; no such bound for IMR.
  double gradientNorm = 0.0;
  /// The smallest ||R|| of the step's iterates (GPHR's Newton; infinity where not tracked): a
  /// failure that came close to the tolerance and stalled is round-off, not divergence.
  double smallestResidualNorm = std::numeric_limits<double>::infinity();
};

/// Options of the Newton solve of each time step: tolerance, iteration cap, Jacobian reuse, predictor.
struct NewtonOptions {
  double tolerance = 1e-10;  ///< on ||R||_2, as the paper's Newton tolerance
  int maxIterations = 25;  ///< Newton iterations allowed per step.
  /// Chord method: assemble (and factor / precondition) the Newton matrix only at the first
  /// iteration of each step. Converges linearly instead of quadratically, but saves the Hessian
  /// assemblies that dominate the reduced model's cost (A^T Hess N A is O(n k^2)).
  bool reuseJacobian = false;
  /// Lagged Newton matrix across steps (as CVODE does): keep the last factored matrix from step to
  /// step and re-assemble only when Newton slows down (||R_{i+1}|| > lagRate ||R_i|| with a stale
  /// matrix), after lagMaxSteps steps, or when dt changes. Same tolerance, far fewer Hessians and
  /// LU factorisations for the reduced and hyper-reduced models.
  bool lagJacobian = false;
  double lagRate = 0.3;  ///< lagJacobian: re-assemble when ||R_{i+1}|| > lagRate ||R_i||.
  int lagMaxSteps = 20;  ///< lagJacobian: re-assemble at the latest after this many steps.
  /// Newton's initial guess for y^{j+1}: the polynomial through the last predictorOrder + 1 states
  /// extrapolated one step (integrate(), extrapolatedGuess()). 3 (cubic) by default: on the
  /// paper's NLS set-up (n = 2048, dt = 0.01, AVF) the full model takes 1.95 Newton iterations per
  /// step against 2.94 with the linear guess, the GP-ADEIM model 2.55 against 2.96.
  int predictorOrder = 3;
};

constexpr int kMaxPredictorOrder = 3;  ///< Largest allowed NewtonOptions::predictorOrder.

/// The one failure message of both Newton drivers (GPHR's loop and NOX): where and how far.
inline std::string newtonFailureMessage(const NewtonOptions& o, long step, double time, const StepReport& rep,
                                        const std::string& driver = "Newton") {
  // A residual that is not finite is an overflow, not slow convergence: say so, since more
  // iterations or a looser tolerance (what the plain message suggests) cannot help.
  const char* overflow = std::isfinite(rep.residualNorm)
                             ? ""
                             : "; not finite: the state or its gradient left the double range (a parameter far "
                               "outside the training box, or too large a step)";
  // Within 100x of the tolerance and no further: the residual's round-off at this state (its terms
  // ~ |y| and dt |J grad H| times the machine epsilon) is above the tolerance.
  const bool stalled = rep.smallestResidualNorm <= 100.0 * o.tolerance;
  return detail::concat(driver, " did not converge at step ", step, " (t = ", time, "): residual norm ",
                        rep.residualNorm, " after ", rep.newtonIterations, " iterations (tolerance ",
                        o.tolerance, ", at most ", o.maxIterations, ")", overflow,
                        stalled ? detail::concat("; it stalled at ", rep.smallestResidualNorm,
                                                 ", within 100x of the tolerance: the residual's round-off at this "
                                                 "state is likely above it; allowed: a larger "
                                                 "integrator.newtonTolerance")
                                : std::string());
}

/// The implicit scheme (*) of the file's description (IMR or AVF by its quadrature rule) over a Backend.
template <class Backend>
class AveragedGradientScheme {
 public:
  using Vector = typename Backend::Vector;  ///< The backend's state vector.

  /// The scheme on `backend` with quadrature `rule` (1-point Gauss: IMR) and Newton options `opts`.
  AveragedGradientScheme(Backend& backend, QuadratureRule rule, NewtonOptions opts)
      : be_(backend), rule_(std::move(rule)), opts_(opts), yq_(be_.create()), gsum_(be_.create()),
        g_(be_.create()), res_(be_.create()), rhs_(be_.create()), dx_(be_.create()) {}

  const QuadratureRule& rule() const { return rule_; }  ///< The quadrature rule (nodes s_q, weights w_q).
  const NewtonOptions& options() const { return opts_; }  ///< The Newton options.

  /// Solve (*) for y1, starting from the guess in y1, with GPHR's own Newton loop (the driver of
  /// the reduced models and, by default, of the full model; the full model's alternative driver is
  /// NOX, NoxNewtonSolver, which calls residual() and assembleNewtonMatrix() below). Throws
  /// SolverError if Newton fails; `step` and `time` only label that message.
  StepReport step(const Vector& y0, Vector& y1, double dt, long step = 0, double time = 0.0) {
    StepReport rep;
    if (opts_.lagJacobian && (dt != lagDt_ || ++lagAge_ > opts_.lagMaxSteps)) haveMatrix_ = false;
    bool fresh = false;  // the current matrix was assembled in this step
    double previous = 0.0;
    for (;;) {
      rep.residualNorm = residual(y0, y1, dt);
      rep.smallestResidualNorm = std::min(rep.smallestResidualNorm, rep.residualNorm);
      if (rep.residualNorm <= opts_.tolerance) {
        rep.gradientNorm = Backend::norm(gsum_);
        return rep;
      }
      GPHR_REQUIRE(std::isfinite(rep.residualNorm) && rep.newtonIterations < opts_.maxIterations,
                   SolverError, newtonFailureMessage(opts_, step, time, rep));
      bool assemble = rep.newtonIterations == 0 || !opts_.reuseJacobian;
      if (opts_.lagJacobian)
        assemble = !haveMatrix_ || (!fresh && rep.newtonIterations > 0 && rep.residualNorm > opts_.lagRate * previous);
      if (assemble) {
        assembleNewtonMatrix(y0, y1, dt);
        ++rep.newtonMatrices;
        fresh = haveMatrix_ = true;
        lagDt_ = dt;
        lagAge_ = 0;
      }
      previous = rep.residualNorm;
      Backend::update(rhs_, -1.0, res_, 0.0);
      rep.linearIterations += be_.solveNewton(rhs_, dx_, opts_.tolerance / rep.residualNorm);
      Backend::update(y1, 1.0, dx_, 1.0);
      ++rep.newtonIterations;
    }
  }

  /// The backend's Newton matrix := K(y0, y1) = I - dt J sum_q w_q s_q Hess H(y0 + s_q (y1 - y0)).
  void assembleNewtonMatrix(const Vector& y0, const Vector& y1, double dt) {
    be_.beginNewtonMatrix();
    if (!be_.addAveragedHessian(y0, y1, rule_, -dt))
      for (int q = 0; q < rule_.size(); ++q) {
        Backend::update(yq_, 1.0 - rule_.nodes[q], y0, rule_.nodes[q], y1, 0.0);
        be_.addHessian(yq_, -dt * rule_.weights[q] * rule_.nodes[q]);
      }
    be_.endNewtonMatrix();
  }

  /// Average gradient gbar = sum_q w_q grad H(y0 + s_q (y1 - y0)) of the last residual() (with
  /// either driver, the last residual evaluated in a step is that of the accepted y1).
  const Vector& averageGradient() const { return gsum_; }

  /// R = y1 - y0 - dt J gbar into R; returns ||R||.
  double residual(const Vector& y0, const Vector& y1, double dt, Vector& R) {
    if (!be_.averagedGradient(y0, y1, rule_, gsum_))
      for (int q = 0; q < rule_.size(); ++q) {
        Backend::update(yq_, 1.0 - rule_.nodes[q], y0, rule_.nodes[q], y1, 0.0);
        be_.gradient(yq_, g_);
        Backend::update(gsum_, rule_.weights[q], g_, q == 0 ? 0.0 : 1.0);
      }
    be_.applyJ(gsum_, R);
    Backend::update(R, 1.0, y1, -1.0, y0, -dt);
    return Backend::norm(R);
  }
  /// R = y1 - y0 - dt J gbar into the scheme's own buffer; returns ||R||.
  double residual(const Vector& y0, const Vector& y1, double dt) { return residual(y0, y1, dt, res_); }

 private:
  Backend& be_;
  QuadratureRule rule_;
  NewtonOptions opts_;
  Vector yq_, gsum_, g_, res_, rhs_, dx_;
  bool haveMatrix_ = false;  ///< lagJacobian: a factored matrix from an earlier step is in the backend
  double lagDt_ = 0.0;
  int lagAge_ = 0;
};

}  // namespace gphr
