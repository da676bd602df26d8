#include "gphr/driver/OfflineStages.hpp"

#include <algorithm>
#include <cstdio>

#include "gphr/driver/Config.hpp"

namespace gphr {

namespace {

// The config that determines the training snapshots: scene, time, integrator, training.
std::string trainingKey(const Teuchos::ParameterList& cfg) {
  Teuchos::ParameterList k("training-stage");
  for (const char* s : {"scene", "time", "integrator", "training"}) k.sublist(s) = cfg.sublist(s);
  return toYaml(k);
}

std::string basisKey(const Teuchos::ParameterList& cfg) {
  // podRoute's default (auto) is what every basis cached before the key existed was computed with
  // (then TSQR where it fit, now the stacked route: both exact SVDs, equal to round-off): it stays
  // out of the key, so those caches remain valid; another route is a different key.
  Teuchos::ParameterList red = cfg.sublist("reduction");
  if (red.isParameter("podRoute") && red.get<std::string>("podRoute") == "auto") red.remove("podRoute");
  return trainingKey(cfg) + toYaml(red) + "k = " + std::to_string(basisK(cfg));
}

int largestM(const Teuchos::ParameterList& cfg) {
  const auto& ms = cfg.sublist("pipeline").get<Teuchos::Array<int>>("m");
  return ms.empty() ? 0 : *std::max_element(ms.begin(), ms.end());  // empty: no hyper-reduced model
}

}  // namespace

int basisK(const Teuchos::ParameterList& cfg) {
  const auto ks = pipelineK(cfg);
  return std::max(cfg.sublist("reduction").get<int>("k"), *std::max_element(ks.begin(), ks.end()));
}

ModelBuildKeys cacheKeys(const Teuchos::ParameterList& cfg) {
  ModelBuildKeys k;
  k.training = trainingKey(cfg);
  k.basis = basisKey(cfg);
  // The DEIM algorithm's revision is part of the key: a basis cached by an earlier one is
  // recomputed (2: the randomized range finder draws random signs instead of Gaussian numbers;
  // 3: the exact route's POD is hierarchical, over chunks of the snapshots).
  // hyper.deimSnapshots configures the classic DEIM baseline only, and hyper.groupSize only who
  // POD's which chunk (the same basis to round-off): both out of this basis's key.
  Teuchos::ParameterList hyper = cfg.sublist("hyper");
  hyper.remove("deimSnapshots", false);
  hyper.remove("groupSize", false);
  k.deim = k.basis + toYaml(hyper) + "deim basis revision 3, m <= " + std::to_string(largestM(cfg));
  k.nnls = k.basis + toYaml(cfg.sublist("eqp"));
  k.refit = k.nnls + toYaml(cfg.sublist("hyper"));  // the refit's terms are GP-DEIM's
  return k;
}

ArtifactsCache artifactsCache(const RunContext& ctx, long fullDim) {
  ArtifactsCache cache(ctx.artifactsPath(), ctx.comm, ctx.scene->name(), fullDim);
  cache.setCheckpointSeconds(ctx.config.sublist("output").get<double>("checkpointSeconds"));
  cache.setSyncToDisk(ctx.config.sublist("output").get<bool>("syncArtifacts"));
  return cache;
}

RomStages runOfflineStages(const RunContext& ctx) {
  const auto inst = ctx.scene->instantiate(ctx.comm, ctx.mu, true);
  const TrainingOptions training = trainingOptionsOf(ctx.config, ctx.scene->parameterBox());
  const BasisOptions basis = basisOptionsFrom(ctx.config.sublist("reduction"), basisK(ctx.config));
  checkBasisSizeBeforeTraining(training, basis, basis.k, inst.system->space().fullDim());  // before any file
  const ArtifactsCache cache = artifactsCache(ctx, inst.system->space().fullDim());
  const ModelBuildKeys keys = cacheKeys(ctx.config);
  RomStages st;
  st.training = runTraining(*ctx.scene, ctx.comm, training, &cache, keys.training);
  const BasisStageResult b =
      runBasisStage(st.training, inst.system->space(), basis, ctx.scene->name(), &cache, keys.basis);
  st.basis = b.basis, st.basisCached = b.cached, st.basisSeconds = b.seconds, st.basisCpuSeconds = b.cpuSeconds;
  if (ctx.comm->getRank() == 0)
    std::fprintf(stderr, "[gphr] reduce: %s basis, 2k = %d, snapshot energy left out 1 - captured = %.1e%s, %.1f s "
                 "(%.1f s CPU; POD steps: %d tsqr, %d stacked, %d tree, %d replicated)\n", st.basis.method.c_str(),
                 2 * st.basis.k, 1.0 - st.basis.energyCaptured, st.basisCached ? " (cached)" : "", st.basisSeconds, st.basisCpuSeconds,
                 st.basis.podSteps.tsqr, st.basis.podSteps.stacked, st.basis.podSteps.tree, st.basis.podSteps.replicated);
  return st;
}

CachedDeimBasis deimBasisFor(const RunContext& ctx, const RomStages& st, const MultiVector& A,
                             const HamiltonianSystem& test) {
  const ArtifactsCache cache = artifactsCache(ctx, test.space().fullDim());
  return runDeimBasisStage(*ctx.scene, ctx.comm, st.training, A, test,
                           deimBasisOptionsFrom(ctx.config.sublist("hyper"), largestM(ctx.config)), &cache,
                           cacheKeys(ctx.config).deim);
}

void setBasisKeys(const RunContext& ctx, const RomStages& st, RunMetrics& run) {
  run.set(Metric::TTrainingS, st.training.seconds)
      .set(Metric::TBasisS, st.basisSeconds)
      .set(Metric::TBasisCpuS, st.basisCpuSeconds)
      .set(Metric::PodRoute, ctx.config.sublist("reduction").get<std::string>("podRoute"))
      .set(Metric::PodStepsTsqr, static_cast<long>(st.basis.podSteps.tsqr))
      .set(Metric::PodStepsReplicated, static_cast<long>(st.basis.podSteps.replicated))
      .set(Metric::PodStepsStacked, static_cast<long>(st.basis.podSteps.stacked))
      .set(Metric::PodStepsTree, static_cast<long>(st.basis.podSteps.tree));
}

}  // namespace gphr
