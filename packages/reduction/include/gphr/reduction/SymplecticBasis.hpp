#pragma once
/// @file
/// Orthonormal symplectic reduced bases A (2n x 2k, A^T A = I, A^T J_{2n} A = J_{2k}) from
/// distributed snapshots (paper Sec.\ 2; constructions of Peng & Mohseni 2016):
///   psd (complex SVD, the paper's choice): U = Phi + i Psi, the leading k left singular vectors
///       of C = Q + i P;  A = [[Phi, -Psi], [Psi, Phi]].
///   cotangent lift: Phi, the leading k left singular vectors of [Q, P];  A = [[Phi, 0], [0, Phi]].
/// Both are one computation in the real representation (a + i b <-> [a; b], i <-> J^T): the data
/// columns D are [q; p] (psd) or [q; 0], [p; 0] (cotangent). X = [D, J^T D], block by block,
/// goes through the generic StreamingPod (incremental TSQR + LAPACK SVD, truncated to 2 maxRank
/// real triplets, as in libROM; the same on any rank count); a complex Gram-Schmidt of its left
/// vectors in the small coordinates keeps one vector of each J-pair. Nothing n x N_snap is
/// gathered and nothing n x n is formed; with all snapshots in one block it is the exact thin SVD.
#include <Teuchos_ParameterList.hpp>
#include <functional>
#include <string>
#include <vector>

#include "gphr/core/PhaseSpace.hpp"
#include "gphr/core/SnapshotSet.hpp"
#include "gphr/reduction/StreamingPod.hpp"

namespace gphr {

/// Options of the symplectic basis: construction, size k, POD blocks and route.
struct BasisOptions {
  std::string method = "psd";      ///< psd | cotangent
  int k = 0;                       ///< basis half-size; 0: from energyTolerance
  double energyTolerance = 1e-6;   ///< discarded fraction of the snapshot energy (when k = 0)
  int blockColumns = 128;          ///< snapshot columns per incremental step
  int maxRank = 0;                 ///< complex triplets kept between steps; 0: 2k + 32 (k given) or 512; at most n
  std::string podRoute = "auto";   ///< auto | tsqr | stacked | tree | replicated: the StreamingPod's step route
};

/// A symplectic, orthonormal reduced basis A with its singular values and POD statistics.
struct ReducedBasis {
  RCP<MultiVector> A;                  ///< 2n x 2k on the state map
  std::vector<double> singularValues;  ///< of the (complex) data matrix, all that were kept
  double energyCaptured = 0.0;         ///< sum_{j<=k} sigma_j^2 / ||C||_F^2
  int k = 0;  ///< k, the basis half-size (A has 2k columns).
  std::string method;  ///< Construction used (psd | cotangent).
  PodSteps podSteps;   ///< streaming POD steps taken by each route
};

/// Where a basis computation stood after whole snapshot blocks (a checkpoint the caller keeps):
/// the blocks done, their energy ||D||_F^2 and the streaming POD's state.
struct BasisProgress {
  size_t blocks = 0;         ///< snapshot blocks (training parameters) done
  double energy = 0.0;       ///< their energy
  StreamingPod::State pod;   ///< the POD after them
};

/// Snapshots: columns of each MultiVector are states y on space.map() (shifted states when the
/// model is shifted). With `resume` (blocks > 0) the computation goes on after its blocks from its
/// state, bit for bit what it would have computed; `save`, if set, gets the progress after each
/// block but the last. Collective.
ReducedBasis computeSymplecticBasis(const SnapshotSet& snapshots, const PhaseSpace& space, const BasisOptions& options,
                                    const BasisProgress* resume = nullptr,
                                    const std::function<void(const BasisProgress&)>& save = {});

/// The largest k a basis of `options` can have from `snapshots` state columns on n dofs, known
/// before the training: min(n, the triplets kept, the POD matrix's columns: 2 per state, [D, J^T D]
/// for psd and [Q, P] for cotangent). Past the states' own rank the basis holds round-off
/// directions (every nonzero sigma is kept); the POD may give fewer nonzero ones than the bound.
long basisRankBound(const BasisOptions& options, GO n, long snapshots);

/// The row map of the basis's streaming POD (the state map for psd, the dof map for cotangent):
/// the map of a BasisProgress's POD state.
RCP<const Map> basisPodMap(const PhaseSpace& space, const BasisOptions& options);

/// The options of a `reduction` configuration section (validated: every key present) for a basis
/// of half-size k (0: chosen by the energy tolerance).
BasisOptions basisOptionsFrom(const Teuchos::ParameterList& reduction, int k);
/// The basis stage's cache key (core/CacheKey.hpp). podRoute auto stays out of it: every basis
/// cached before the route was an option was computed so (the routes are exact SVDs, equal to
/// round-off); another route is another key.
std::string basisCacheKey(const BasisOptions& options);
/// The keys of a `reduction` section with their defaults, ranges and documentation: what
/// basisOptionsFrom() reads (and `k`, the reduced size of `gphr run`).
Teuchos::ParameterList basisValidParameters();

/// The leading 2k columns of a symplectic basis of size kb: [E_k, J^T E_k] = columns [0, k) and
/// [kb, kb + k) (still orthonormal and symplectic).
RCP<MultiVector> leadingBasis(const ReducedBasis& basis, int k);

/// The reduced sizes asked for, 0 standing for the basis's own k; InputError for a k above it.
std::vector<int> basisSizes(const std::vector<int>& ks, const ReducedBasis& basis);

}  // namespace gphr
