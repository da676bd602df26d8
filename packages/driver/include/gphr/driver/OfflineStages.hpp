#pragma once
/// @file
/// The offline stages as `gphr run` and `gphr build` configure them (the stages themselves are
/// packages/offline): their options and artifacts-cache keys from the configuration, and the
/// results of `gphr run`'s training and basis stages with the reduced models evaluated after them.
#include <string>
#include <vector>

#include "gphr/driver/ModelRun.hpp"
#include "gphr/driver/RunContext.hpp"
#include "gphr/offline/BasisStage.hpp"
#include "gphr/offline/DeimBasisStage.hpp"
#include "gphr/offline/ModelFileBuild.hpp"
#include "gphr/offline/Training.hpp"

namespace gphr {

/// The offline stages of `gphr run` and the reduced models they produced.
struct RomStages {
  TrainingResult training;  ///< The training stage.
  ReducedBasis basis;  ///< The symplectic basis A.
  bool basisCached = false;  ///< Whether the basis was read from artifacts.h5.
  double basisSeconds = 0.0;  ///< Wall seconds of the basis stage.
  double basisCpuSeconds = 0.0;           ///< rank 0's process CPU time in the basis stage
  std::vector<ModelRun> runs;             ///< rom, then the hyper-reduced models
  std::vector<double> deimSingularValues; ///< of the reduced-Jacobian snapshots (largest k)
};

/// The k the basis is built for: the largest of reduction.k and pipeline.k.
int basisK(const Teuchos::ParameterList& cfg);
/// The artifacts-cache keys of a configuration: the config text each stage depends on.
ModelBuildKeys cacheKeys(const Teuchos::ParameterList& cfg);
/// DIR/artifacts.h5 of the run's scene and state size 2n = fullDim. Collective.
ArtifactsCache artifactsCache(const RunContext& ctx, long fullDim);
/// The training and basis stages of the configuration, through the artifacts cache, with the
/// basis stage's progress line. Collective.
RomStages runOfflineStages(const RunContext& ctx);
/// The reduced-Jacobian DEIM basis of size k for the basis A (section hyper), from the cache in
/// artifacts.h5 `/deim/k<k>` when its key matches, else computed from the training snapshots and
/// cached. `test` supplies the row map of G. Collective.
CachedDeimBasis deimBasisFor(const RunContext& ctx, const RomStages& st, const MultiVector& A,
                             const HamiltonianSystem& test);
/// The training and basis keys of a rom / gp-deim entry: t_training_s, t_basis_s, t_basis_cpu_s,
/// pod_route and the basis's POD steps by route.
void setBasisKeys(const RunContext& ctx, const RomStages& stages, RunMetrics& run);

}  // namespace gphr
