#include "gphr/online/TimeLoop.hpp"

#include <Teuchos_Time.hpp>
#include <cmath>

#include "gphr/core/Error.hpp"
#include "gphr/hyper/GpAdeimModel.hpp"
#include "gphr/timeint/DenseModelIntegrator.hpp"

namespace gphr {

long wholeSteps(double T, double dt) {
  GPHR_REQUIRE(std::isfinite(dt) && dt > 0 && std::isfinite(T) && T >= dt, InputError, "T = ", T, ", dt = ", dt,
               "; allowed: dt > 0 and T >= dt");
  const double ratio = T / dt;
  const long steps = std::lround(ratio);
  GPHR_REQUIRE(std::abs(ratio - steps) <= 1e-9 * ratio, InputError, "T = ", T, " is not a whole number of steps dt = ",
               dt, " (T / dt = ", ratio, ")");
  return steps;
}

SimulationStats simulate(DenseHamiltonian& model, const SimulationSettings& settings, DenseVector& z,
                         const StepHook& observe, const StepHook& adapt) {
  SimulationStats stats;
  DenseModelIntegrator integ(model, settings.integrator, settings.polynomialDegree);
  z.shape(model.dim(), 1);  // zero: the shifted initial state
  Teuchos::Time wall("online"), obs("observe");
  wall.start();
  try {
    stats.run = integ.run(z, settings.dt, settings.steps, [&](long j, double t, const DenseVector& zj, const StepReport&) {
      obs.start(true);
      stats.lastStep = j;
      for (int i = 0; i < zj.length(); ++i)
        GPHR_REQUIRE(std::isfinite(zj(i)), SolverError, "non-finite reduced state at step ", j);
      if (observe) observe(j, t, zj);
      stats.observeSeconds += obs.stop();
      if (adapt) adapt(j, t, zj);
    });
  } catch (const SolverError& e) {
    stats.status = "diverged";
    stats.reason = e.what();
    if (obs.isRunning()) stats.observeSeconds += obs.stop();
  }
  stats.onlineSeconds = wall.stop() - stats.observeSeconds;
  return stats;
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
