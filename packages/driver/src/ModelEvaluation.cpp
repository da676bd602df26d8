#include "gphr/driver/ModelEvaluation.hpp"

#include <Teuchos_Time.hpp>

#include <cmath>
#include <cstdio>
#include <limits>

#include "gphr/core/Progress.hpp"
#include "gphr/driver/FieldModels.hpp"

namespace gphr {

ModelRun evaluateRun(const EvaluationSettings& settings, const FomResult& fom, const HamiltonianSystem& system,
                     const MultiVector& A, DenseHamiltonian& model, const RunSpec& spec) {
  const bool fieldStates = fom.fieldStates && fom.fieldStates->wants(spec.method);
  ReducedRunOptions options;
  options.hasHamiltonian = methodInfo(spec.method).hasHamiltonian();
  options.keepStates = fieldStates;
  options.adapt = spec.adapt;
  ModelRun run;
  run.method = spec.method, run.k = spec.k, run.m = spec.m, run.steps = settings.time.steps;
  options.label = run.label();
  Teuchos::Time clock("evaluation");
  clock.start();
  static_cast<ReducedEvaluation&>(run) = evaluateReducedModel(settings, fom, system, A, model, options);
  const bool root = A.getMap()->getComm()->getRank() == 0;
  // A run the watcher spoke of (longer than the progress interval) has its end said too.
  const double every = ProgressWatch::seconds();
  if (run.ok && root && every > 0.0 && clock.stop() >= every)
    progressLine("[gphr] %s: done, E_L2 = %.3g, online %.3g s", run.label().c_str(), run.eL2, run.tOnline);
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
