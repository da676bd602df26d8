#pragma once
/// @file
/// Integrator configuration (IMR / AVF, Newton) and the generic time loop over
/// AveragedGradientScheme, shared by the full, reduced and hyper-reduced models.
#include <Teuchos_ParameterList.hpp>
#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "gphr/timeint/AveragedGradientScheme.hpp"

namespace gphr {

/// Valid keys: scheme (imr|avf), quadraturePoints (0 = from G's degree), newtonTolerance,
/// maxNewtonIterations, jacobianReuse, jacobianLag (with jacobianLagRate, jacobianLagMaxSteps),
/// newtonPredictor (0..3), newtonSolver (nox|gphr, full model only), and the sections
/// linearSolver (FullModelBackend::validParameters()) and nox (noxValidParameters()).
Teuchos::ParameterList integratorValidParameters();
/// A user's `integrator` section validated against integratorValidParameters(), its defaults
/// filled in: what every integrator (full, dense, the scheme residual) and driftBound read.
Teuchos::ParameterList validatedIntegrator(Teuchos::ParameterList integrator);

/// The `nox` section: top-level keys of NOX's parameter list; its sections (Direction, Line Search,
/// Trust Region, Printing, Solver Options) are passed through to NOX unchecked.
Teuchos::ParameterList noxValidParameters();

/// IMR: the 1-point Gauss rule. AVF: Gauss-Legendre with quadraturePoints nodes, or when 0 the
/// fewest that are exact for G of polynomial degree `degree` (a non-polynomial G, degree 0, gets 3).
QuadratureRule quadratureFor(const std::string& scheme, int quadraturePoints, int degree);
/// Whether quadratureFor's rule integrates the averaged gradient exactly for G of polynomial
/// degree `degree` (0: unknown, never): then the scheme is a discrete gradient and
/// RunStats::driftBound bounds the drift of H (AVF with enough points; IMR for degree <= 2).
bool quadratureIsExact(const std::string& scheme, int quadraturePoints, int degree);
/// Newton options of the `integrator` section.
NewtonOptions newtonOptionsFrom(const Teuchos::ParameterList& integrator);

/// Statistics of a time integration: steps, Newton and linear iterations, residuals, wall time.
struct RunStats {
  long steps = 0;  ///< Time steps taken.
  long newtonIterations = 0;  ///< Newton iterations over all steps.
  long linearIterations = 0;  ///< Linear (Krylov) iterations over all steps.
  long newtonMatrices = 0;  ///< Newton matrices assembled (dense models: LU factorisations)
  double maxResidual = 0.0;  ///< Largest Newton residual accepted.
  /// Sum over the steps of ||gbar|| ||R|| (StepReport::gradientNorm): with AVF's exact rule,
  /// |H(y^j) - H(y^0)| <= driftBound at every step j, beyond the round-off of evaluating H.
  double driftBound = 0.0;
  double wallSeconds = 0.0;  ///< Wall seconds of the time loop.
};

/// Observer called at step 0 (initial state) and after every step: (step, time, state, report).
template <class Vector>
using StepObserver = std::function<void(long, double, const Vector&, const StepReport&)>;

/// The Newton guess for y^{j+1}: the polynomial through y^j and the p previous states past[0] =
/// y^{j-1}, ..., past[p-1] = y^{j-p}, extrapolated one step, sum_{i=0..p} (-1)^i binom(p+1, i+1)
/// y^{j-i} (p = 0: y^j; 1: 2 y^j - y^{j-1}; 3: 4 y^j - 6 y^{j-1} + 4 y^{j-2} - y^{j-3}). Exact
/// for states that are polynomials of degree <= p in the step index; on a smooth trajectory the
/// guess is O(dt^{p+1}) from y^{j+1}, so fewer Newton iterations reach the same tolerance.
template <class Backend, class PastState>
void extrapolatedGuess(const typename Backend::Vector& y, int p, const PastState& past,
                       typename Backend::Vector& next) {
  // Row p: (-1)^i binom(p + 1, i + 1), i = 0 .. p.
  static constexpr double kCoefficients[kMaxPredictorOrder + 1][kMaxPredictorOrder + 1] = {
      {1.0}, {2.0, -1.0}, {3.0, -3.0, 1.0}, {4.0, -6.0, 4.0, -1.0}};
  if (p == 0) {
    Backend::assign(next, y);
    return;
  }
  const double* c = kCoefficients[p];
  Backend::update(next, c[0], y, c[1], past(0), 0.0);
  for (int i = 2; i <= p; ++i) Backend::update(next, c[i], past(i - 1), 1.0);
}

/// Advance y by `steps` steps of size dt from time t0. The Newton guess for y^{j+1} is
/// extrapolatedGuess of order min(predictorOrder, states at hand): a run (or a resumed run) starts
/// from y^0, then linear, quadratic, ... Stepper: AveragedGradientScheme (GPHR's Newton loop) or
/// NoxNewtonSolver, both with step(y0, y1, dt, stepNo, t) -> StepReport.
template <class Stepper, class Backend>
RunStats integrate(Stepper& scheme, Backend& backend, typename Backend::Vector& y, double dt, long steps,
                   const StepObserver<typename Backend::Vector>& observer, int predictorOrder, double t0 = 0.0,
                   long firstStep = 0) {
  using V = typename Backend::Vector;
  GPHR_REQUIRE(predictorOrder >= 0 && predictorOrder <= kMaxPredictorOrder, InputError, "Newton predictor order ",
               predictorOrder, " is not allowed (0 to ", kMaxPredictorOrder, ")");
  RunStats stats;
  // The last predictorOrder states in a ring: one copy per step (of the state being left).
  std::vector<V> ring;
  for (int i = 0; i < predictorOrder; ++i) ring.push_back(backend.create());
  int head = -1, have = 0;  // ring[head] = y^{j-1}, ring[head - 1] = y^{j-2}, ... (mod order)
  auto past = [&](int i) -> const V& { return ring[(head - i + predictorOrder) % predictorOrder]; };
  V next = backend.create();
  if (observer) observer(firstStep, t0, y, StepReport{});
  for (long j = 0; j < steps; ++j) {
    extrapolatedGuess<Backend>(y, std::min(predictorOrder, have), past, next);
    const long stepNo = firstStep + j + 1;
    const double t = t0 + (j + 1) * dt;
    const StepReport rep = scheme.step(y, next, dt, stepNo, t);
    if (predictorOrder > 0) {
      head = (head + 1) % predictorOrder;
      Backend::assign(ring[head], y);
      have = std::min(have + 1, predictorOrder);
    }
    Backend::assign(y, next);
    stats.steps++;
    stats.newtonIterations += rep.newtonIterations;
    stats.linearIterations += rep.linearIterations;
    stats.newtonMatrices += rep.newtonMatrices;
    stats.maxResidual = std::max(stats.maxResidual, rep.residualNorm);
    stats.driftBound += rep.gradientNorm * rep.residualNorm;
    if (observer) observer(stepNo, t, y, rep);
  }
  return stats;
}

}  // namespace gphr
