#include "gphr/driver/OfflineStages.hpp"

#include <cstdio>

namespace gphr {

ArtifactsCache artifactsCache(const RunContext& ctx, const RunOptions& options, long fullDim) {
  ArtifactsCache cache(ctx.artifactsPath(), ctx.comm, options.scene->name(), fullDim);
  cache.setCheckpointSeconds(options.output.checkpointSeconds);
  cache.setSyncToDisk(options.output.syncArtifacts);
  return cache;
}

RomStages runOfflineStages(const RunContext& ctx, const RunOptions& options) {
  const auto& o = options.offline;
  RomStages st;
  // The instance first (the run evaluates its models on it): its size checks k before any file.
  st.offline = std::make_shared<OfflineSequence>(*options.scene, ctx.comm, o, options.mu);
  const GO fullDim = st.offline->instance().system->space().fullDim();
  checkBasisSizeBeforeTraining(o.training, o.basis, o.basis.k, fullDim);
  st.offline->setCache(artifactsCache(ctx, options, fullDim));
  st.training = st.offline->training();
  const BasisStageResult& b = st.offline->basis();
  st.basis = b.basis, st.basisCached = b.cached, st.basisSeconds = b.seconds, st.basisCpuSeconds = b.cpuSeconds;
  // The captured share is a ratio of sums of squared singular values, exact to a few hundred eps:
  // below 1e-12 what is left out is round-off (printed as such rather than as -4.0e-15).
  const double leftOut = 1.0 - st.basis.energyCaptured;
  char left[64];
  if (leftOut < 1e-12) std::snprintf(left, sizeof left, "below round-off (< 1e-12)");
  else std::snprintf(left, sizeof left, "%.1e", leftOut);
  if (ctx.comm->getRank() == 0)
    std::fprintf(stderr, "[gphr] reduce: %s basis, 2k = %d, snapshot energy left out 1 - captured = %s%s, %.1f s "
                 "(%.1f s CPU; POD steps: %d tsqr, %d stacked, %d tree, %d replicated)\n", st.basis.method.c_str(),
                 2 * st.basis.k, left, st.basisCached ? " (cached)" : "", st.basisSeconds, st.basisCpuSeconds,
                 st.basis.podSteps.tsqr, st.basis.podSteps.stacked, st.basis.podSteps.tree, st.basis.podSteps.replicated);
  return st;
}

void setBasisKeys(const RunOptions& options, const RomStages& st, RunMetrics& run) {
  run.set(Metric::TTrainingS, st.training.seconds)
      .set(Metric::TBasisS, st.basisSeconds)
      .set(Metric::TBasisCpuS, st.basisCpuSeconds)
      .set(Metric::PodRoute, options.offline.basis.podRoute)
      .set(Metric::PodStepsTsqr, static_cast<long>(st.basis.podSteps.tsqr))
      .set(Metric::PodStepsReplicated, static_cast<long>(st.basis.podSteps.replicated))
      .set(Metric::PodStepsStacked, static_cast<long>(st.basis.podSteps.stacked))
      .set(Metric::PodStepsTree, static_cast<long>(st.basis.podSteps.tree));
}

}  // namespace gphr
