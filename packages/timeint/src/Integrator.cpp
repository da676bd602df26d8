#include "gphr/timeint/Integrator.hpp"

#include "gphr/core/ParameterValidation.hpp"
#include "gphr/timeint/FullModelBackend.hpp"

namespace gphr {

Teuchos::ParameterList integratorValidParameters() {
  Teuchos::ParameterList pl("integrator");
  setChoiceParameter(pl, "scheme", "avf", Teuchos::tuple<std::string>("imr", "avf"),
                     "imr: implicit midpoint (symplectic); avf: Average Vector Field (conserves H)");
  setIntParameter(pl, "quadraturePoints", 0, 0, 64,
                  "AVF Gauss-Legendre points; 0 = fewest exact for the scene's G");
  setDoubleParameter(pl, "newtonTolerance", 1e-10, 1e-15, 1e-2,
                     "Newton stops when ||R||_2 <= this (the paper uses 1e-10)");
  setIntParameter(pl, "maxNewtonIterations", 25, 1, 1000, "Newton iteration limit per step");
  pl.set("jacobianReuse", false,
         "chord Newton: the Newton matrix is assembled once per step (cheaper reduced models, linear convergence)");
  pl.set("jacobianLag", false,
         "keep the Newton matrix (and its LU) across steps and re-assemble only when Newton slows down, as CVODE "
         "does (GPHR's Newton; same tolerance, far fewer Hessians for reduced and hyper-reduced models)");
  setDoubleParameter(pl, "jacobianLagRate", 0.3, 1e-3, 0.99,
                     "with jacobianLag: re-assemble when ||R|| shrinks by less than this factor in one iteration");
  setIntParameter(pl, "jacobianLagMaxSteps", 20, 1, 1000000, "with jacobianLag: re-assemble at least every N steps");
  setIntParameter(pl, "newtonPredictor", 3, 0, kMaxPredictorOrder,
                  "Newton's initial guess: the polynomial through the last p + 1 states extrapolated one step (0: "
                  "the last state, 1: linear, 3: cubic; higher orders need fewer Newton iterations on smooth "
                  "trajectories, same tolerance)");
  setChoiceParameter(pl, "newtonSolver", "gphr", Teuchos::tuple<std::string>("gphr", "nox"),
                     "Newton driver of the full model's steps: gphr (GPHR's own loop) or nox (NOX::Thyra, configured "
                     "by the nox section: line searches, trust regions; same iterates with its defaults, ~15-25% more "
                     "CPU time, see doc/design.md, 'Newton'); reduced models always use GPHR's loop (dense LU)");
  pl.sublist("linearSolver") = FullModelBackend::validParameters();
  pl.sublist("nox") = noxValidParameters();
  return pl;
}

Teuchos::ParameterList validatedIntegrator(Teuchos::ParameterList integrator) {
  validateParameters(integrator, integratorValidParameters(), "integrator");
  return integrator;
}

Teuchos::ParameterList noxValidParameters() {
  Teuchos::ParameterList pl("nox");
  setChoiceParameter(pl, "Nonlinear Solver", "Line Search Based",
                     Teuchos::tuple<std::string>("Line Search Based", "Trust Region Based", "Inexact Trust Region Based"),
                     "NOX solver; the status test is always ||R||_2 <= newtonTolerance or maxNewtonIterations "
                     "reached (failure) or a non-finite R (failure)");
  setPassThroughSection(pl, "Direction",
                        "NOX Direction (default Method: Newton; Newton.Linear Solver.Tolerance defaults to "
                        "linearSolver.tolerance)");
  setPassThroughSection(pl, "Line Search", "NOX Line Search, e.g. Method: Full Step (default), Backtrack, Polynomial");
  setPassThroughSection(pl, "Trust Region", "NOX Trust Region options of the trust-region solvers");
  setPassThroughSection(pl, "Printing", "NOX Printing (default Output Information: 0, errors only)");
  setPassThroughSection(pl, "Solver Options", "NOX Solver Options");
  return pl;
}

QuadratureRule quadratureFor(const std::string& scheme, int quadraturePoints, int degree) {
  if (scheme == "imr") return gaussLegendre(1);
  GPHR_REQUIRE(scheme == "avf", InputError, "integrator scheme '", scheme, "' is not one of 'imr', 'avf'");
  if (quadraturePoints > 0) return gaussLegendre(quadraturePoints);
  return gaussLegendre(degree > 0 ? gaussPointsForDegree(degree) : 3);
}

bool quadratureIsExact(const std::string& scheme, int quadraturePoints, int degree) {
  if (degree <= 0) return false;
  const int points = scheme == "imr" ? 1 : quadraturePoints > 0 ? quadraturePoints : gaussPointsForDegree(degree);
  return points >= gaussPointsForDegree(degree);  // Gauss-Legendre with q points: exact to degree 2q - 1
}

NewtonOptions newtonOptionsFrom(const Teuchos::ParameterList& pl) {
  NewtonOptions o;
  o.tolerance = pl.get<double>("newtonTolerance");
  o.maxIterations = pl.get<int>("maxNewtonIterations");
  o.reuseJacobian = pl.get<bool>("jacobianReuse");
  o.lagJacobian = pl.get<bool>("jacobianLag");
  o.lagRate = pl.get<double>("jacobianLagRate");
  o.lagMaxSteps = pl.get<int>("jacobianLagMaxSteps");
  o.predictorOrder = pl.get<int>("newtonPredictor");
  return o;
}

}  // namespace gphr
