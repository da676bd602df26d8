#pragma once
/// @file
/// A streaming POD (incremental thin SVD) of a tall matrix given block by block on any Tpetra
/// map: only the current rank-r factor U diag(sigma) and one block are ever held.
///   add(X):   Y = [U diag(sigma), X];  Y = Q W S Z^T (the step's route, below);
///             U <- Q W(:, 1:r'),  sigma <- S(1:r'),  r' = min(maxRank, numerical rank).
/// With every column in one block it is the exact thin SVD; truncating to maxRank between blocks
/// is the incremental SVD of libROM / Brand 2002 (error bounded by the discarded sigma's).
/// Steps take blockColumns columns each, on any rank count, so the truncations and the result are
/// the same on 1, 2 or 3 ranks up to round-off. Each step takes one of four routes, all exact:
///   tsqr:       TSQR needs (carried + new columns) <= rows on every rank;
///   replicated: [U diag(sigma), X] gathered on every rank, one LAPACK SVD there (d x columns
///               numbers per rank, and every rank does the whole SVD: it takes any rank count but
///               does not get faster with more ranks).
///   stacked:    a TSQR with LAPACK kernels: each rank's rows by a Householder QR in row chunks
///               (HouseholderQr: GEQRT, TPQRT; any row count), the R factors stacked on every
///               rank and one GESDD of the stack, each rank's rows of U by the chunks' Q; its
///               local work divides with the ranks, it takes any rank count, and where ranks
///               hold fewer rows than columns it costs about what `replicated` costs.
///   tree:       the stacked route with the R factors reduced over a binary tree of ranks
///               (TreeTsqr.hpp) instead of stacked on every rank: one QR of two stacked c x c
///               triangles per level (LAPACK TPQRT), one c x c SVD on rank 0; its replicated work
///               grows with log2 p, not with p.
/// PodRoute::Auto (the default) takes the tree route from 2 ranks on (one rank: the stacked route,
/// the same work): with the structured QR at its levels its steps are measured 1.1-1.3x faster than
/// the stacked route's on 2 ranks, 1.5x on 3, 1.8x on 4, and more with p (doc/design.md,
/// 'Symplectic bases and the streaming POD').
/// Tsqr refuses a step that does not fit (InputError naming its columns and the rows per rank);
/// the other routes take every step.
#include <string>
#include <vector>

#include "gphr/core/Types.hpp"

namespace gphr {

class HouseholderQr;

/// Route of a streaming POD step (the file's description): auto, tsqr, stacked, tree or replicated.
enum class PodRoute { Auto, Tsqr, Stacked, Tree, Replicated };
/// "auto" | "tsqr" | "stacked" | "tree" | "replicated" (the config's podRoute values); anything else: InputError.
PodRoute podRouteFromName(const std::string& name);
/// The route names podRouteFromName() takes, in the order --help lists them.
std::vector<std::string> podRouteNames();
/// The rank count from which auto takes the tree route.
constexpr int kTreeRouteFromRanks = 2;
/// The route a step takes on `ranks` ranks: `route`, or for Auto stacked below kTreeRouteFromRanks, else tree.
PodRoute stepRoute(PodRoute route, int ranks);

/// ||X(:, j)||^2 of every column, summed over the ranks (collective). Each column's rows are read
/// as one contiguous run by BLAS DOT: KokkosBlas' multivector norm on the Serial backend walks each
/// row across all columns, a page apart in a tall block, and took 3.6 % of the SWE 256^2 build.
std::vector<double> columnSquaredNorms(const MultiVector& X);

/// Steps a streaming POD took, by route: one type for every stage's statistics, metrics and
/// checkpoints, so that a count is summed, stored and read in one place.
struct PodSteps {
  /// steps by the tsqr, replicated, stacked and tree routes
  /// @{
  int tsqr = 0, replicated = 0, stacked = 0, tree = 0;
  /// @}
  static constexpr int kFields = 4;  ///< numbers in put/get: tsqr, replicated, stacked, tree
  int total() const { return tsqr + replicated + stacked + tree; }  ///< Steps by all routes.
  /// Adds another POD's steps route by route (a root's and its chunks').
  PodSteps& operator+=(const PodSteps& o) {
    tsqr += o.tsqr, replicated += o.replicated, stacked += o.stacked, tree += o.tree;
    return *this;
  }
  /// As kFields numbers at out (a checkpoint's or a reduction's array).
  void put(double* out) const { out[0] = tsqr, out[1] = replicated, out[2] = stacked, out[3] = tree; }
  /// From kFields numbers written by put.
  static PodSteps get(const double* in) { return {int(in[0]), int(in[1]), int(in[2]), int(in[3])}; }
};

/// A streaming POD (incremental thin SVD) of a tall distributed matrix given block by block.
class StreamingPod {
 public:
  /// maxRank: singular triplets kept between steps; blockColumns: new columns per step;
  /// rankTolerance: sigma_j <= rankTolerance * sigma_1 are dropped (< 0: columns * machine eps,
  /// LAPACK's numerical rank; 0: keep every nonzero one); route: see above.
  StreamingPod(RCP<const Map> map, int maxRank, int blockColumns, double rankTolerance = -1.0,
               PodRoute route = PodRoute::Auto);

  void add(const MultiVector& X);  ///< collective; X on map()
  /// Where a POD stood after some steps, enough to go on from there (a checkpoint): the left vectors
  /// (map x sigma.size()), the singular values, the energy and columns added, the steps by route.
  struct State {
    RCP<const MultiVector> U;   ///< left vectors, map x max(sigma.size(), 1)
    std::vector<double> sigma;  ///< singular values, descending
    double energy = 0.0;        ///< ||all columns added||_F^2
    long columns = 0;           ///< columns added
    PodSteps steps;             ///< steps taken by each route
  };
  State state() const;  ///< This POD's state (U shared: later steps replace the POD's U, never overwrite it).
  /// Goes on from `s` (a state of a POD of the same map and maxRank): the next add gives what the
  /// POD that held `s` would give, bit for bit. Collective.
  void restore(const State& s);
  const RCP<const Map>& map() const { return map_; }  ///< The row map of the matrix.
  int rank() const { return static_cast<int>(sigma_.size()); }  ///< Current rank r (singular triplets held).
  /// Left singular vectors (map x rank(); an empty MultiVector of one zero column while rank() == 0).
  const MultiVector& leftVectors() const { return *U_; }
  const std::vector<double>& singularValues() const { return sigma_; }  ///< The singular values sigma, descending.
  double totalEnergy() const { return energy_; }  ///< ||all columns added||_F^2
  long columnsAdded() const { return columns_; }  ///< Columns added so far.
  int blockColumns() const { return blockColumns_; }  ///< Columns per step.
  const PodSteps& steps() const { return steps_; }  ///< Steps taken by each route so far.

 private:
  void step(const MultiVector& X, size_t c0, size_t c1);
  std::vector<double> leafColumns(const MultiVector& X, size_t c0, size_t c1);  // Y's rows here, column-major
  MultiVector stepMatrix(const MultiVector& X, size_t c0, size_t c1) const;       // Y as a MultiVector
  void replicatedStep(const MultiVector& Y);
  void tsqrStep(MultiVector& Y);
  void stackedStep(std::vector<double> y, int nc);  // y: this rank's rows of Y, column-major
  void treeStep(std::vector<double> y, int nc);
  void setLeftVectors(HouseholderQr& leaf, const std::vector<double>& C, int keep);
  int truncate(const std::vector<double>& S, int nc);
  RCP<const Map> map_;
  int maxRank_, blockColumns_;
  double rankTolerance_;
  PodRoute route_;
  int cap_;
  PodSteps steps_;
  RCP<MultiVector> U_;
  std::vector<double> work_;  // the leaf's array, kept from step to step (see step())
  std::vector<double> sigma_;
  double energy_ = 0.0;
  long columns_ = 0;
};

}  // namespace gphr
