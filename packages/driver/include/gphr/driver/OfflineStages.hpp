#pragma once
/// @file
/// `gphr run`'s offline stages: the library's OfflineSequence (packages/offline, the same one
/// `gphr build` and a user's code run) on DIR/artifacts.h5, with the run's progress line of the
/// basis, and the reduced models evaluated after them.
#include <memory>
#include <string>
#include <vector>

#include "gphr/driver/ModelRun.hpp"
#include "gphr/driver/RunContext.hpp"
#include "gphr/driver/RunOptions.hpp"
#include "gphr/offline/OfflineSequence.hpp"

namespace gphr {

/// The offline stages of `gphr run` and the reduced models they produced.
struct RomStages {
  std::shared_ptr<OfflineSequence> offline;  ///< the stages; the DEIM bases and fits are asked of it per k
  TrainingResult training;  ///< The training stage.
  ReducedBasis basis;  ///< The symplectic basis A.
  bool basisCached = false;  ///< Whether the basis was read from artifacts.h5.
  double basisSeconds = 0.0;  ///< Wall seconds of the basis stage.
  double basisCpuSeconds = 0.0;           ///< rank 0's process CPU time in the basis stage
  std::vector<ModelRun> runs;             ///< rom, then the hyper-reduced models
  std::vector<double> deimSingularValues; ///< of the reduced-Jacobian snapshots (largest k)
};

/// DIR/artifacts.h5 of the run's scene and state size 2n = fullDim. Collective.
ArtifactsCache artifactsCache(const RunContext& ctx, const RunOptions& options, long fullDim);
/// The training and basis stages of the configuration, through the artifacts cache, with the
/// basis stage's progress line. Collective.
RomStages runOfflineStages(const RunContext& ctx, const RunOptions& options);
/// The training and basis keys of a rom / gp-deim entry: t_training_s, t_basis_s, t_basis_cpu_s,
/// pod_route and the basis's POD steps by route.
void setBasisKeys(const RunOptions& options, const RomStages& stages, RunMetrics& run);

}  // namespace gphr
