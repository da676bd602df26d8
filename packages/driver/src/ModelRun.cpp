#include "gphr/driver/ModelRun.hpp"

#include <cmath>
#include <limits>

namespace gphr {

std::string ModelRun::label() const {
  return method + " k=" + std::to_string(k) + (m > 0 ? " m=" + std::to_string(m) : "");
}

// The keys in summary.json's order since its first version: identity, accuracy, the time loop,
// status; then the stage's own (which may replace one in place: GP-ADEIM's local H_hr drift).
JsonObject ModelRun::json() const {
  RunMetrics e;
  e.set(Metric::Method, method).set(Metric::K, static_cast<long>(k));
  if (!available) {
    e.set(Metric::M, static_cast<long>(m)).set(Metric::Status, statusName(RunStatus::Unavailable));
    return e.merge(metrics).json();
  }
  e.set(Metric::ReducedDim, static_cast<long>(2 * k));
  if (m > 0) e.set(Metric::M, static_cast<long>(m));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  e.set(Metric::Steps, steps)
      .set(Metric::EL2, eL2)
      .set(Metric::EFin, eFinal)
      .set(Metric::EL2Estimate, errorEstimate)
      .set(Metric::HErrMax, hamiltonianErrorMax)
      .set(Metric::HErrFinal, hamiltonianErrorFinal)
      .set(Metric::HErrMaxRel, hamiltonianErrorMaxRelative)
      .set(Metric::TOnlineS, tOnline)
      .set(Metric::TOnlineRunsS, onlineTimes)
      .set(Metric::NewtonItersAvg, ok ? double(stats.newtonIterations) / steps : nan)
      .set(Metric::NewtonMatrices, ok ? stats.newtonMatrices : -1L)
      .set(Metric::HDriftBound, driftBound)
      .set(Metric::ErrorsAt, "saved steps (every output.saveEvery-th and the last)");
  if (unboundedAt >= 0) e.set(Metric::UnboundedAtStep, unboundedAt).set(Metric::UnboundedReason, unboundedReason);
  e.set(Metric::Status, statusName(status()));
  if (!std::isnan(modelHamiltonianDrift)) e.set(Metric::HModelErrMax, modelHamiltonianDrift);
  if (!ok) e.set(Metric::DivergedAtStep, lastStep + 1).set(Metric::DivergedReason, divergedReason);
  return e.merge(metrics).json();
}

}  // namespace gphr
