#pragma once
/// @file
/// The DEIM-basis stage: the reduced-Jacobian DEIM basis U of GP-DEIM (hyper package, paper
/// Sec. 3) at reduced size k from the training snapshots, read from the artifacts cache
/// (`/deim/k<k>`) when its key matches, else computed and cached with the time it took.
#include <string>

#include "gphr/hyper/DeimBasis.hpp"
#include "gphr/offline/ArtifactsCache.hpp"
#include "gphr/offline/Training.hpp"

namespace gphr {

/// The most state rows per rank of a rank group of the DEIM basis stage (its memory bound: each
/// group holds the whole basis A).
constexpr long kDeimRowsPerRank = 1L << 18;

/// A DEIM basis and where it came from.
struct CachedDeimBasis {
  DeimBasis basis;              ///< The reduced-Jacobian DEIM basis.
  bool cached = false;          ///< Whether it was read from the cache.
  double seconds = 0.0;         ///< this call: computing it, or reading the cache
  double computeSeconds = 0.0;  ///< computing it (stored with the cache): the offline cost it stands for
};

/// The DEIM basis of `training`'s snapshots for the basis A (2n x 2k) of `scene`. `reference`,
/// any instance of the scene, supplies the row map of G; `key`: what the basis depends on besides k
/// (the stage completes it with k). An InputError of the computation is
/// prefixed with `section` (the configuration section its options came from). Collective.
CachedDeimBasis runDeimBasisStage(const Scene& scene, const RCP<const Comm>& comm, const TrainingResult& training,
                                  const MultiVector& A, const HamiltonianSystem& reference,
                                  const DeimBasisOptions& options, const ArtifactsCache* cache = nullptr,
                                  const std::string& key = "", const std::string& section = "hyper");

}  // namespace gphr
