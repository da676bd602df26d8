#pragma once
/// @file
/// The pieces of a communication-avoiding TSQR (Demmel, Grigori, Hoemmen, Langou 2012) on small
/// dense blocks, for StreamingPod's `tree` route:
///   HouseholderQr: one block's QR by LAPACK GEQRF, its R and Q [C; 0] by ORMQR;
///   TreeTsqr:      a binary-tree reduction of the ranks' R factors over ceil(log2 p) levels (at
///                  each level a rank stacks its R on its partner's and factors the stack), and
///                  the tree's Q applied back down to each rank's block.
/// Each level's QR is at most 2c x c for c columns, and the root's R is c x c: the work a rank
/// does beyond its own rows is O(log2(p) c^3), against the stacked route's O(p c^3) on every rank.
#include <algorithm>
#include <vector>

#include "gphr/core/Types.hpp"

namespace gphr {

/// Householder QR of an m x n column-major block (any shape): k = min(m, n) reflectors.
class HouseholderQr {
 public:
  HouseholderQr() = default;
  /// Factors a (m x n, column-major, leading dimension m; taken over). SolverError if LAPACK fails.
  HouseholderQr(int m, int n, std::vector<double> a);
  int rows() const { return m_; }             ///< m, the block's rows
  int k() const { return std::min(m_, n_); }  ///< rows of R
  /// R: k() x n upper trapezoidal, column-major (leading dimension k()).
  std::vector<double> r() const;
  /// Q [C; 0] (m x cols, column-major) for C (k() x cols, column-major): Q's first k() columns times C.
  std::vector<double> applyQ(const std::vector<double>& C, int cols) const;

 private:
  int m_ = 0, n_ = 0;
  std::vector<double> a_, tau_;
};

/// A binary-tree reduction of one R factor per rank to rank 0 and back (collective over comm).
/// Level s = 1, 2, 4, ...: rank q with q % 2s == s sends its R to q - s and waits; rank q with
/// q % 2s == 0 and q + s < p stacks [R_q; R_{q+s}] and factors it. Any p (a rank without a
/// partner at a level passes its R up unchanged).
class TreeTsqr {
 public:
  /// A tree over comm's ranks for R factors of `columns` columns (comm must outlive it).
  TreeTsqr(const Comm& comm, int columns) : comm_(comm), n_(columns) {}
  /// R: this rank's k x n factor (column-major). Returns the root's R (K x n, K = min(sum k, n))
  /// on rank 0 and an empty vector elsewhere; K in *rootRows on rank 0.
  std::vector<double> reduce(std::vector<double> R, int k, int* rootRows);
  /// C: on rank 0 the root's K x cols block (ignored elsewhere). Returns this rank's block of the
  /// tree's Q applied to [C; 0]: (its k) x cols, column-major. After reduce; collective.
  std::vector<double> applyQ(std::vector<double> C, int cols) const;

 private:
  struct Level {
    int partner, mine;  ///< the rank whose R was stacked below this rank's, and this rank's rows in the stack
    HouseholderQr qr;
  };
  const Comm& comm_;
  int n_;
  std::vector<Level> levels_;   ///< the levels where this rank factored a stack, bottom up
  int parent_ = -1, sent_ = 0;  ///< the rank this one sent its R to (-1: the root), and its rows
};

}  // namespace gphr
