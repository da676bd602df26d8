#pragma once
/// @file
/// The basis stage: the symplectic basis A from all training snapshots (reduction package), read
/// from the artifacts cache (`/basis`, its columns as rows) when its key matches, else computed
/// and cached with its provenance.
#include <string>

#include "gphr/offline/ArtifactsCache.hpp"
#include "gphr/offline/Training.hpp"
#include "gphr/reduction/SymplecticBasis.hpp"

namespace gphr {

/// The basis of the training snapshots and whether it came from the cache.
struct BasisStageResult {
  ReducedBasis basis;      ///< The symplectic basis A.
  bool cached = false;     ///< Whether the basis was read from the cache.
  double seconds = 0.0;    ///< Wall seconds of the stage.
  double cpuSeconds = 0.0; ///< rank 0's process CPU seconds of the stage
};

/// The basis of `training`'s snapshots on `space` (see the file's description). A cached basis of
/// another k than options.k (when set) is an InputError naming the cache. Collective.
BasisStageResult runBasisStage(const TrainingResult& training, const PhaseSpace& space, const BasisOptions& options,
                               const std::string& sceneName, const ArtifactsCache* cache = nullptr,
                               const std::string& key = "");

/// Refuses (InputError) a basis half-size k that no training of `training`'s size gives on
/// fullDim / 2 dofs (basisRankBound), before the training runs: without this a k past the bound
/// failed only after it. fullDim <= 0 or k <= 0: nothing checked.
void checkBasisSizeBeforeTraining(const TrainingOptions& training, const BasisOptions& options, int k, GO fullDim);

}  // namespace gphr
