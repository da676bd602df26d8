#pragma once
/// @file
/// The DEIM basis of GP-DEIM (paper sec:ConstrDEIM): POD of the reduced-Jacobian snapshots
///   M_J = [ J_G(y0_j + A A^T y_s) A ]   (eq:snaps_JG, shifted: y_s = y - y0_j),
/// d x 2k per kept training state, streamed into an incremental SVD (StreamingPod) or a
/// randomized range finder, so that M_J (d x 2k x states: 5 GB at the paper's NLS sizes) is never held.
#include <Teuchos_ParameterList.hpp>
#include <algorithm>
#include <string>
#include <vector>

#include "gphr/core/HamiltonianSystem.hpp"
#include "gphr/core/SnapshotSet.hpp"
#include "gphr/core/SystemSet.hpp"
#include "gphr/hyper/JacobianSnapshots.hpp"
#include "gphr/reduction/StreamingPod.hpp"

namespace gphr {

/// Options of the DEIM basis: its rank, the snapshots used, and the SVD (exact streaming POD or randomized).
struct DeimBasisOptions {
  int maxRank = 0;        ///< singular triplets kept between blocks (>= the largest m wanted); 0: deimMaxRank()
  int largestM = 0;       ///< the largest DEIM size wanted (0: not known), which maxRank 0 keeps room for
  int snapshotEvery = 1;  ///< use every N-th stored training state (the paper: 20)
  int blockSnapshots = 0; ///< reduced-Jacobian snapshots (2k columns each) per POD step; 0: ~maxRank columns
  /// exact: reduced-Jacobian snapshots per chunk of the hierarchical POD (DeimChunks); 0: about
  /// kChunkColumnsPerRank x maxRank columns per chunk, equal chunks.
  int chunkSnapshots = 0;
  /// exact, in the offline stage with an artifacts cache: ranks per rank group POD'ing chunks side
  /// by side; 0: automatic (offline/DeimBasisStage.hpp); >= the ranks: all ranks together.
  int groupSize = 0;
  /// exact: the streaming POD (incremental TSQR + SVD); randomized: the range finder of HMT11
  /// (one streamed pass + powerIterations passes + one for B B^T), oversampling extra columns.
  std::string svd = "exact";
  std::string podRoute = "auto";  ///< exact: the StreamingPod's step route (auto | tsqr | stacked | tree | replicated)
  int oversampling = 10;  ///< randomized: extra columns of the range finder.
  int powerIterations = 1;  ///< randomized: power iterations (passes over the snapshots).
  /// randomized, its last pass (B = Q^T M_J): true, by the Gram matrix B B^T (one small GEMM per
  /// snapshot; resolves sigma down to ~1e-7 sigma_1, enough for the DEIM sizes worth using);
  /// false, by a blocked QR of the stacked B^T (~eps sigma_1; a few times the Gram's cost), for a
  /// basis that must keep directions far down the spectrum (GP-ADEIM's initial U_0: m of them).
  bool gramProjection = true;
  unsigned long long seed = 20231122;  ///< randomized: seed of the test matrix (random signs).
};

/// The options of a `hyper` configuration section (validated: every key present); largestM: the
/// largest DEIM size wanted (DeimBasisOptions::largestM: what maxRank 0 keeps, deimMaxRank()).
DeimBasisOptions deimBasisOptionsFrom(const Teuchos::ParameterList& hyper, int largestM);
/// The DEIM basis stage's cache key (core/CacheKey.hpp): every option that changes the basis, with
/// maxRank as asked for (deimMaxRank before its cap at d, which the scene fixes) and the algorithm's revision (3: the exact route's
/// POD is hierarchical, over chunks of the snapshots; 2: the range finder draws random signs).
/// groupSize (who POD's which chunk, the same basis to round-off) is left out.
std::string deimBasisCacheKey(const DeimBasisOptions& options);
/// The keys of a `hyper` section with their defaults, ranges and documentation: the DEIM basis
/// (deimBasisOptionsFrom), its interpolation indices and the classic DEIM baseline's snapshots.
Teuchos::ParameterList deimBasisValidParameters();

constexpr int kDefaultDeimRank = 400;  ///< maxRank 0 without a largest m: the triplets kept.
constexpr int kDeimRankMargin = 32;    ///< maxRank 0 with a largest m: the triplets kept beyond it.
/// The DEIM basis' numerical rank: its vectors are the left singular vectors of the snapshots whose
/// singular values exceed kDeimRankFloor sigma_1, in every POD of the exact route that decides it
/// (the streaming POD of a chunk and of the chunks' root; the randomized route's Gram projection
/// resolves only to 1e-7 sigma_1, above it). The
/// snapshots carry round-off of their own (the training trajectories', ~1e-13 sigma_1 at most:
/// SWE 20 x 20, whose snapshot matrix has rank 63 by an independent SVD, shows sigma_64 = 4e-14 on
/// one rank and 1.0e-13 on three), and the streaming POD carries it from step to step, so the
/// former floor of n_cols eps (~3e-14) kept a BLAS-dependent number of round-off directions there
/// (79 vectors on one OpenBLAS thread, 80 on two). 1e-12 is 10x above the largest round-off
/// measured and 2.6x below the smallest real direction in the test suite's cases (NLS n = 32:
/// sigma_9 = 2.6e-12 sigma_1, then 2e-16): the count is the same on any kernel, thread and rank count.
constexpr double kDeimRankFloor = 1e-12;

/// The DEIM basis U (d x rank) of GP-DEIM with the singular values and snapshot statistics of its POD.
struct DeimBasis {
  RCP<MultiVector> U;                  ///< d x rank, on the row map of G
  std::vector<double> singularValues;  ///< of M_J (the leading ones kept)
  long snapshots = 0;                  ///< reduced-Jacobian snapshots (states) used
  double energy = 0.0;                 ///< ||M_J||_F^2
  PodSteps podSteps;  ///< svd exact: the streaming POD's steps by route (hyper.podRoute); all 0 for randomized
};

/// The exact route's chunks. Its POD is hierarchical (HAPOD: Himpe, Leibner & Rave, SIAM J. Sci.
/// Comput. 40 (2018), the distributed two-level tree of their Sec. 3.2): the used snapshots, in
/// order, are cut into chunks; each chunk's reduced-Jacobian snapshots go through a streaming POD
/// of their own, truncated at maxRank, and the chunks' modes U_q diag(sigma_q), in chunk order,
/// through one more (the root). Each truncation drops only singular values below the kept ones,
/// and the root's error is bounded by the chunks' and its own discarded sigma's (HAPOD Thm. 3.1).
/// Why chunks: a streaming POD step costs a replicated SVD of (maxRank + block) columns that no
/// rank count divides (at the paper's NLS size ~0.2 s of every 0.3 s step); chunks are
/// independent, so rank groups POD them side by side (offline/DeimBasisStage), and a root over
/// (chunks x maxRank) columns adds one step per chunk. The chunks are fixed by the data
/// (snapshot count, maxRank, 2k), not by the ranks: the basis is the same on any rank count and
/// any group split, to round-off.
struct DeimChunks {
  long snapshots = 0;  ///< used snapshots in all
  long perChunk = 1;   ///< snapshots per chunk (the last may hold fewer)
  int count() const { return static_cast<int>((snapshots + perChunk - 1) / perChunk); }  ///< Number of chunks.
  SnapshotRange range(int q) const { return {q * perChunk, std::min(snapshots, (q + 1) * perChunk)}; }  ///< Chunk q.
};
constexpr int kChunkColumnsPerRank = 32;  ///< Default chunk size: about this many times maxRank columns.
/// The chunks of the used snapshots of `states` for 2k = r basis columns and maxRank triplets:
/// options.chunkSnapshots per chunk, or (0) about kChunkColumnsPerRank maxRank / r, evened out.
DeimChunks deimChunks(const SnapshotSet& states, const DeimBasisOptions& options, int r, int maxRank);

/// One chunk's POD: its modes U_q diag(sigma_q) (rank columns; one zero column when rank is 0).
struct DeimChunkModes {
  RCP<MultiVector> modes;  ///< on the row map of G of the systems given
  int rank = 0;            ///< triplets kept
  double energy = 0.0;     ///< ||the chunk's snapshots||_F^2
  long snapshots = 0;      ///< snapshots POD'd
  PodSteps podSteps;       ///< POD steps by route
};
/// The POD of the reduced-Jacobian snapshots in `range` (the exact route, maxRank triplets); with
/// `cache`, shared by the calls for consecutive chunks, a block cut by two chunks is read once.
/// Collective over the systems' communicator.
DeimChunkModes deimChunkModes(const SystemSet& systems, const SnapshotSet& states,
                              const MultiVector& A, const DeimBasisOptions& options, int maxRank, SnapshotRange range,
                              ReducedStateCache* cache = nullptr);
/// The largest DEIM rank the options keep for a row map of d rows, at most d: options.maxRank, or
/// for 0 (the default, the one place it is decided) largestM + kDeimRankMargin, or kDefaultDeimRank
/// where no largest m is known.
int deimMaxRank(const DeimBasisOptions& options, GO d);

/// The root of the hierarchical POD: a streaming POD of the chunks' modes U_q diag(sigma_q), one
/// step per chunk, added in chunk order (so that it holds one chunk's modes at a time besides its
/// own maxRank triplets); the chunks' statistics are summed into the basis. Collective.
class DeimRootPod {
 public:
  /// A root on rowMap (the row map of G) keeping maxRank triplets; options: its podRoute.
  DeimRootPod(RCP<const Map> rowMap, const DeimBasisOptions& options, int maxRank);
  /// Chunk `stats`'s modes: the leading stats.rank columns of `modes` (on the row map).
  void add(const MultiVector& modes, const DeimChunkModes& stats);
  DeimBasis basis() const;  ///< The DEIM basis of the chunks added so far.
  /// A checkpoint of the chunks added so far: the root POD's state and the chunks' summed
  /// statistics (modes unset); restore(state(), statistics()) goes on bit for bit.
  StreamingPod::State state() const { return pod_.state(); }
  const DeimChunkModes& statistics() const { return sum_; }  ///< The chunks' summed statistics.
  void restore(const StreamingPod::State& state, const DeimChunkModes& statistics);  ///< Collective.

 private:
  StreamingPod pod_;
  DeimChunkModes sum_;
};

/// systems[j]: the (shifted) system at training parameter j; states[j]: its stored states in the
/// system's own coordinates. A: the reduced basis (2n x 2k). Collective.
DeimBasis computeDeimBasis(const SystemSet& systems,
                           const SnapshotSet& states, const MultiVector& A,
                           const DeimBasisOptions& options);

}  // namespace gphr
