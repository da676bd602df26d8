#include "gphr/driver/ModelEvaluation.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include "gphr/driver/Config.hpp"
#include "gphr/driver/FieldModels.hpp"

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

std::vector<int> stageK(const Teuchos::ParameterList& cfg, const ReducedBasis& basis) {
  return basisSizes(pipelineK(cfg), basis);
}

ModelRun evaluateRun(const EvaluationSettings& settings, const FomResult& fom, const HamiltonianSystem& system,
                     const MultiVector& A, DenseHamiltonian& model, const RunSpec& spec) {
  const bool fieldStates = fom.fieldStates && fom.fieldStates->wants(spec.method);
  ReducedRunOptions options;
  options.hasHamiltonian = methodInfo(spec.method).hasHamiltonian();
  options.keepStates = fieldStates;
  options.adapt = spec.adapt;
  ModelRun run;
  static_cast<ReducedEvaluation&>(run) = evaluateReducedModel(settings, fom, system, A, model, options);
  run.method = spec.method, run.k = spec.k, run.m = spec.m, run.steps = settings.time.steps;
  const bool root = A.getMap()->getComm()->getRank() == 0;
  if (run.unboundedAt >= 0 && root)
    std::fprintf(stderr, "[gphr] %s unbounded from step %ld: %s\n", run.label().c_str(), run.unboundedAt,
                 run.unboundedReason.c_str());
  if (!run.ok && root)
    std::fprintf(stderr, "[gphr] %s diverged at step %ld: %s\n", run.label().c_str(), run.lastStep + 1,
                 run.divergedReason.c_str());
  // The states go to the field outputs, which keep them only while this run is the most accurate
  // of a name of output.fieldModels; nothing else reads them.
  if (fieldStates) fom.fieldStates->offer(run);
  run.states.clear();
  return run;
}

}  // namespace gphr
