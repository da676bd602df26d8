#include "gphr/online/TimeLoop.hpp"

#include <cmath>

#include "gphr/core/Error.hpp"
#include "gphr/hyper/GpAdeimModel.hpp"
#include "gphr/timeint/DenseModelIntegrator.hpp"

namespace gphr {

long wholeSteps(double T, double dt) {
  GPHR_REQUIRE(std::isfinite(dt) && dt > 0 && std::isfinite(T) && T >= dt, InputError, "T = ", T, ", dt = ", dt,
               "; allowed: dt > 0 and T >= dt");
  const double ratio = T / dt;
  GPHR_REQUIRE(ratio < 9e15, InputError, "T / dt = ", ratio, " (T = ", T, ", dt = ", dt,
               "); allowed: below 9e15, where steps are still whole numbers in a double");
  const long steps = std::lround(ratio);
  GPHR_REQUIRE(std::abs(ratio - steps) <= 1e-9 * ratio, InputError, "T = ", T, " is not a whole number of steps dt = ",
               dt, " (T / dt = ", ratio, ")");
  return steps;
}

SimulationStats simulate(DenseHamiltonian& model, const SimulationSettings& settings, DenseVector& z,
                         const StepHook& observe, const StepHook& adapt) {
  DenseModelIntegrator integ(model, settings.integrator, settings.polynomialDegree);
  z.shape(model.dim(), 1);  // zero: the shifted initial state
  return observedTimeLoop(integ, z, settings.dt, settings.steps, observe, adapt);
}

StepHook adeimUpdateHook(GpAdeimModel& model) {
  return [&model](long j, double, const DenseVector& z) {
    try {
      model.afterStep(j, z);
    } catch (const InputError& e) {  // a degenerate update mid-run is a result, not a crash
      throw SolverError(detail::concat("GP-ADEIM update after step ", j, ": ", e.what()));
    }
  };
}

}  // namespace gphr
