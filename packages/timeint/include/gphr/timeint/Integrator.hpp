#pragma once
// Integrator configuration (IMR / AVF, Newton) and the generic time loop over
// AveragedGradientScheme, shared by the full, reduced and hyper-reduced models.
#include <Teuchos_ParameterList.hpp>
#include <functional>
#include <string>

#include "gphr/timeint/AveragedGradientScheme.hpp"

namespace gphr {

// Valid keys: scheme (imr|avf), quadraturePoints (0 = from G's degree), newtonTolerance,
// maxNewtonIterations, jacobianReuse, newtonSolver (nox|gphr, full model only), and the sections
// linearSolver (FullModelBackend::validParameters()) and nox (noxValidParameters()).
Teuchos::ParameterList integratorValidParameters();

// The `nox` section: top-level keys of NOX's parameter list; its sections (Direction, Line Search,
// Trust Region, Printing, Solver Options) are passed through to NOX unchecked.
Teuchos::ParameterList noxValidParameters();

// IMR: the 1-point Gauss rule. AVF: Gauss-Legendre with quadraturePoints nodes, or when 0 the
// fewest that are exact for G of polynomial degree `degree` (a non-polynomial G, degree 0, gets 3).
QuadratureRule quadratureFor(const std::string& scheme, int quadraturePoints, int degree);
NewtonOptions newtonOptionsFrom(const Teuchos::ParameterList& integrator);

struct RunStats {
  long steps = 0;
  long newtonIterations = 0;
  long linearIterations = 0;
  long newtonMatrices = 0;  // Newton matrices assembled (dense models: LU factorisations)
  double maxResidual = 0.0;
  double wallSeconds = 0.0;
};

// Observer called at step 0 (initial state) and after every step: (step, time, state, report).
template <class Vector>
using StepObserver = std::function<void(long, double, const Vector&, const StepReport&)>;

// Advance y by `steps` steps of size dt from time t0. The Newton guess for y^{j+1} is the linear
// extrapolation 2 y^j - y^{j-1} (y^0 for the first step). Stepper: AveragedGradientScheme (GPHR's
// Newton loop) or NoxNewtonSolver, both with step(y0, y1, dt, stepNo, t) -> StepReport.
template <class Stepper, class Backend>
RunStats integrate(Stepper& scheme, Backend& backend, typename Backend::Vector& y,
                   double dt, long steps, const StepObserver<typename Backend::Vector>& observer,
                   double t0 = 0.0, long firstStep = 0) {
  using V = typename Backend::Vector;
  RunStats stats;
  V prev = backend.create(), next = backend.create();
  Backend::assign(prev, y);
  if (observer) observer(firstStep, t0, y, StepReport{});
  for (long j = 0; j < steps; ++j) {
    Backend::update(next, 2.0, y, -1.0, prev, 0.0);
    const long stepNo = firstStep + j + 1;
    const double t = t0 + (j + 1) * dt;
    const StepReport rep = scheme.step(y, next, dt, stepNo, t);
    Backend::assign(prev, y);
    Backend::assign(y, next);
    stats.steps++;
    stats.newtonIterations += rep.newtonIterations;
    stats.linearIterations += rep.linearIterations;
    stats.newtonMatrices += rep.newtonMatrices;
    stats.maxResidual = std::max(stats.maxResidual, rep.residualNorm);
    if (observer) observer(stepNo, t, y, rep);
  }
  return stats;
}

}  // namespace gphr
