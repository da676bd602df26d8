#pragma once
/// @file
/// The pieces of a communication-avoiding TSQR (Demmel, Grigori, Hoemmen, Langou 2012) on small
/// dense blocks, for StreamingPod's `tree` route:
///   HouseholderQr:    one block's QR as a sequential TSQR over chunks of its rows (LAPACK GEQRT,
///                     then TPQRT of each further chunk onto the running R), its Q by GEMQRT/TPMQRT;
///   TriangleStackQr:  the QR of an n x n upper triangle stacked on an upper trapezoid by LAPACK
///                     TPQRT, which skips the zeros below both diagonals, and its Q by TPMQRT;
///   TreeTsqr:         a binary-tree reduction of the ranks' R factors over ceil(log2 p) levels
///                     (at each level a rank stacks its R on its partner's and factors the stack),
///                     and the tree's Q applied back down to each rank's block.
/// Each level's QR is at most 2c x c for c columns, and the root's R is c x c: the work a rank
/// does beyond its own rows is O(log2(p) c^3), against the stacked route's O(p c^3) on every rank.
#include <algorithm>
#include <variant>
#include <vector>

#include "gphr/core/Types.hpp"

namespace gphr {

/// Householder QR of an m x n column-major block (any shape): k = min(m, n) reflectors. A tall
/// block is factored as a sequential TSQR (Demmel et al. 2012, Sec. 3.2) over chunks of its rows:
/// the first chunk (at least n rows) by GEQRT, each further chunk by TPQRT onto the running n x n
/// R, so that each factorization works on a chunk x n panel that stays in cache. Why not GEQRF
/// of the whole block: reference LAPACK's GEQRF factors each 32-column panel of all m rows by the
/// Level-2 GEQR2 (one pass over the m x 32 panel per column), which streams the block from memory
/// 32 times a panel; ranks that share a node's memory bandwidth then slow each other down. Same
/// Householder arithmetic in another order, same backward stability. `bench/pod_tree_micro leaf`
/// times both side by side: 1.36x at 65536 x 232 with Q applied to 112 columns (the SWE 256^2 DEIM
/// basis' step on one rank), 1.14x at 32768 rows with two ranks side by side (this 2-core VM).
class HouseholderQr {
 public:
  static constexpr int kChunkRows = 2048;  ///< rows of a chunk (2048 x 232 doubles: 3.8 MB)
  HouseholderQr() = default;
  /// Factors a (m x n, column-major, leading dimension m; taken over) in chunks of chunkRows rows
  /// (the first chunk max(chunkRows, n) rows). SolverError if LAPACK fails.
  HouseholderQr(int m, int n, std::vector<double> a, int chunkRows = kChunkRows);
  int rows() const { return m_; }             ///< m, the block's rows
  int k() const { return std::min(m_, n_); }  ///< rows of R
  /// row chunks factored (0 if k() = 0: nothing is)
  int chunks() const { return start_.empty() ? 0 : static_cast<int>(start_.size()) - 1; }
  /// R: k() x n upper trapezoidal, column-major (leading dimension k()).
  std::vector<double> r() const;
  /// Q [C; 0] (m x cols, column-major) for C (k() x cols, column-major): Q's first k() columns times C.
  std::vector<double> applyQ(const std::vector<double>& C, int cols) const;
  /// The same into `out` (m x cols, leading dimension ldo >= m), e.g.\ a MultiVector's own storage.
  void applyQInto(const std::vector<double>& C, int cols, double* out, int ldo) const;
  /// Hands back the array the block was factored in (its reflectors; at least rows() x n numbers)
  /// for the caller to reuse; the QR is empty afterwards.
  std::vector<double> releaseStorage();

 private:
  double* t(int chunk) { return t_.data() + static_cast<size_t>(nb_) * n_ * chunk; }
  const double* t(int chunk) const { return t_.data() + static_cast<size_t>(nb_) * n_ * chunk; }
  int m_ = 0, n_ = 0, nb_ = 1;
  std::vector<double> a_;      ///< the reflectors, chunk by chunk in place (m x n)
  std::vector<double> t_;      ///< each chunk's block reflector factor T (nb x n)
  std::vector<double> top_;    ///< the running R (n x n) when there is more than one chunk
  std::vector<int> start_;     ///< chunk c holds rows start_[c] .. start_[c + 1]
};

/// QR of [T; B]: T an n x n upper triangle, B a kb x n upper trapezoid (kb <= n; zeros below the
/// diagonal are not read), by LAPACK TPQRT (compact WY, the triangle-on-triangle case L = kb).
/// A tree level's stack of two R factors is such a pair: GEQRF of the dense 2n x n stack does
/// 10/3 n^3 flops and its ORMQR about 6 n^2 cols (cols carried back down), TPQRT about n^3 (its
/// T included) and TPMQRT 2 n^2 cols, since each reflector has j + 1 nonzeros instead of n + j.
/// One core of the 2-core VM, factor and Q applied to n / 2 columns: 8.6 -> 2.6 ms per level at
/// n = 232, 37.6 -> 11.0 ms at n = 400 (timed by hand; `pod_tree_micro kernels` prints whole steps).
class TriangleStackQr {
 public:
  TriangleStackQr() = default;
  /// Factors [top; below] (column-major, leading dimensions n and kb; taken over).
  TriangleStackQr(int n, std::vector<double> top, int kb, std::vector<double> below);
  int rows() const { return n_ + kb_; }  ///< n + kb, the stack's rows
  int k() const { return n_; }           ///< rows of R
  /// R: n x n upper triangular, column-major.
  std::vector<double> r() const;
  /// Q [C; 0] ((n + kb) x cols, column-major) for C (n x cols, column-major).
  std::vector<double> applyQ(const std::vector<double>& C, int cols) const;

 private:
  int n_ = 0, kb_ = 0, nb_ = 1;
  std::vector<double> a_, v_, t_;  ///< R (n x n), the reflectors' trapezoid (kb x n), T (nb x n)
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
    /// TriangleStackQr where this rank's R is a full n x n triangle; GEQRF of the dense stack where
    /// it is a trapezoid (a rank with fewer rows than columns).
    std::variant<HouseholderQr, TriangleStackQr> qr;
  };
  const Comm& comm_;
  int n_;
  std::vector<Level> levels_;   ///< the levels where this rank factored a stack, bottom up
  int parent_ = -1, sent_ = 0;  ///< the rank this one sent its R to (-1: the root), and its rows
};

}  // namespace gphr
