// The small dense factorizations behind GP-ADEIM, tested against exact identities and against
// LAPACK's own column-pivoted QR (GEQP3):
// - denseQrFactorR (blocked GEQRT): R^T R = A^T A and R upper triangular, to round-off;
// - pivotedCholeskyInverse (PSTRF + TRTRI) of G = U^T U: U Pi R^{-1} has orthonormal columns,
//   the pivots are GEQP3's on U (both take the largest remaining column norm first), and a
//   rank-deficient G reports its rank.
// - TriangleStackQr (TPQRT, the tree TSQR's level): Q [R; 0] reproduces the stacked triangles, Q's
//   columns are orthonormal, and R equals GEQRF's of the dense stack up to the signs of its rows;
//   with a trapezoid or nothing below.
// - HouseholderQr (the TSQR leaf: GEQRT of a first chunk of rows, TPQRT of the others): the same
//   three identities on one chunk, several, a short last chunk, and fewer rows than columns.
// Tolerances: the matrices are random with entries O(1), so the backward errors are a small
// multiple of n eps ||A||^2 ~ 1e-13 here; orthonormality from a Gram matrix loses cond(G) eps,
// and the test matrix below has cond(G) = 1e4 (column scales 1 .. 1e-2), so 1e-10.
#include <gtest/gtest.h>

#include <Teuchos_LAPACK.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "gphr/core/Error.hpp"
#include "gphr/reduction/DenseQr.hpp"
#include "gphr/reduction/PivotedCholesky.hpp"
#include "gphr/reduction/TreeTsqr.hpp"

using namespace gphr;

namespace {

// m x n, column-major, entries N(0, 1) times the column's scale (decreasing geometrically from 1
// to minScale, columns then shuffled so that the pivot order is not the identity).
DenseMatrix randomColumns(int m, int n, double minScale, unsigned seed) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> nd;
  std::vector<int> order(n);
  for (int j = 0; j < n; ++j) order[j] = j;
  std::shuffle(order.begin(), order.end(), gen);
  DenseMatrix A(m, n);
  for (int j = 0; j < n; ++j) {
    const double scale = n > 1 ? std::pow(minScale, static_cast<double>(order[j]) / (n - 1)) : 1.0;
    for (int i = 0; i < m; ++i) A(i, j) = scale * nd(gen);
  }
  return A;
}

DenseMatrix gram(const DenseMatrix& A) {
  DenseMatrix G(A.numCols(), A.numCols());
  G.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, A, A, 0.0);
  return G;
}

double maxAbsDiff(const DenseMatrix& A, const DenseMatrix& B) {
  double e = 0.0;
  for (int j = 0; j < A.numCols(); ++j)
    for (int i = 0; i < A.numRows(); ++i) e = std::max(e, std::abs(A(i, j) - B(i, j)));
  return e;
}

}  // namespace

TEST(DenseQr, RFactorReproducesTheGramMatrix) {
  for (const auto& [m, n] : {std::pair<int, int>{250, 100}, {40, 7}, {33, 33}}) {  // blocked, small, square
    const DenseMatrix A = randomColumns(m, n, 1.0, 7u + m);
    DenseMatrix a(A), R(n, n);
    denseQrFactorR(m, n, a.values(), a.stride(), R.values(), R.stride(), "test");
    for (int j = 0; j < n; ++j)
      for (int i = j + 1; i < n; ++i) EXPECT_EQ(R(i, j), 0.0);
    const DenseMatrix G = gram(A), RtR = gram(R);
    EXPECT_LT(maxAbsDiff(G, RtR), 1e-12 * G.normInf()) << m << " x " << n;
  }
}

TEST(DenseQr, WideMatrixIsRefused) {
  DenseMatrix a(3, 5), R(5, 5);
  EXPECT_THROW(denseQrFactorR(3, 5, a.values(), a.stride(), R.values(), R.stride(), "test"), InputError);
}

namespace {
// LAPACK GEQRF's R (min(m, n) x n, column-major) of the m x n column-major a: the reference.
std::vector<double> geqrfR(int m, int n, std::vector<double> a) {
  const int k = std::min(m, n);
  std::vector<double> tau(std::max(k, 1)), work(1), R(static_cast<size_t>(k) * n, 0.0);
  Teuchos::LAPACK<int, double> lapack;
  int info = 0;
  lapack.GEQRF(m, n, a.data(), m, tau.data(), work.data(), -1, &info);
  work.resize(static_cast<size_t>(work[0]));
  lapack.GEQRF(m, n, a.data(), m, tau.data(), work.data(), static_cast<int>(work.size()), &info);
  EXPECT_EQ(info, 0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < std::min(k, j + 1); ++i) R[i + static_cast<size_t>(k) * j] = a[i + static_cast<size_t>(m) * j];
  return R;
}

// max |R - diag(+-1) Rref| over a k x n pair (column-major): R is unique up to its rows' signs.
double rowSignDiff(const std::vector<double>& R, const std::vector<double>& Rref, int k, int n) {
  double e = 0.0;
  for (int i = 0; i < k; ++i) {
    const double sign = (R[i + static_cast<size_t>(k) * i] > 0) == (Rref[i + static_cast<size_t>(k) * i] > 0) ? 1.0 : -1.0;
    for (int j = 0; j < n; ++j) e = std::max(e, std::abs(R[i + static_cast<size_t>(k) * j] - sign * Rref[i + static_cast<size_t>(k) * j]));
  }
  return e;
}

// max |Q^T Q - I| over Q's m x k columns (column-major).
double orthonormalityError(const std::vector<double>& Q, int m, int k) {
  double e = 0.0;
  for (int a = 0; a < k; ++a)
    for (int b = 0; b < k; ++b) {
      double dot = 0.0;
      for (int i = 0; i < m; ++i) dot += Q[i + static_cast<size_t>(m) * a] * Q[i + static_cast<size_t>(m) * b];
      e = std::max(e, std::abs(dot - (a == b ? 1.0 : 0.0)));
    }
  return e;
}

std::vector<double> identity(int k) {
  std::vector<double> I(static_cast<size_t>(k) * k, 0.0);
  for (int i = 0; i < k; ++i) I[i + static_cast<size_t>(k) * i] = 1.0;
  return I;
}

double maxAbsDiff(const std::vector<double>& a, const std::vector<double>& b) {
  double e = 0.0;
  for (size_t i = 0; i < a.size(); ++i) e = std::max(e, std::abs(a[i] - b[i]));
  return e;
}

// An m x n upper trapezoid (column-major), entries N(0, 1) on and above the diagonal.
std::vector<double> trapezoid(int m, int n, unsigned seed) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> nd;
  std::vector<double> a(static_cast<size_t>(m) * n, 0.0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < std::min(m, j + 1); ++i) a[i + static_cast<size_t>(m) * j] = nd(gen);
  return a;
}
}  // namespace

// The stack [T; B] (n + kb rows) is what one tree level factors; every entry is O(1), so
// Householder's backward error is a small multiple of (n + kb) eps ~ 1e-14: 1e-12 leaves room.
TEST(TriangleStackQr, FactorsTheStackOfTwoTrianglesAsGeqrfDoes) {
  const int n = 45;  // above the TPQRT panel of 32: two panels
  for (int kb : {n, 20, 0}) {
    SCOPED_TRACE(kb);
    const std::vector<double> T = trapezoid(n, n, 11u), B = trapezoid(kb, n, 12u + kb);
    const int m = n + kb;
    std::vector<double> stack(static_cast<size_t>(m) * n);
    for (int j = 0; j < n; ++j) {
      std::copy_n(T.begin() + static_cast<size_t>(n) * j, n, stack.begin() + static_cast<size_t>(m) * j);
      std::copy_n(B.begin() + static_cast<size_t>(kb) * j, kb, stack.begin() + n + static_cast<size_t>(m) * j);
    }
    const TriangleStackQr qr(n, T, kb, B);
    ASSERT_EQ(qr.rows(), m);
    ASSERT_EQ(qr.k(), n);
    const std::vector<double> R = qr.r();
    const std::vector<double> Q = qr.applyQ(identity(n), n), QR = qr.applyQ(R, n);  // Q [I; 0], Q [R; 0]
    EXPECT_LT(rowSignDiff(R, geqrfR(m, n, stack), n, n), 1e-12 * n);
    EXPECT_LT(orthonormalityError(Q, m, n), 1e-12);
    EXPECT_LT(maxAbsDiff(QR, stack), 1e-12 * n);
    for (int j = 0; j < n; ++j)
      for (int i = j + 1; i < n; ++i) EXPECT_EQ(R[i + static_cast<size_t>(n) * j], 0.0);
  }
}

TEST(TriangleStackQr, RefusesATrapezoidTallerThanTheTriangle) {
  EXPECT_THROW(TriangleStackQr(3, std::vector<double>(9), 4, std::vector<double>(12)), InputError);
}

// The leaf QR in chunks of 64 rows (the library's chunks are 2048 rows; 64 makes several chunks of
// a small block): one chunk (m <= 64), a first chunk of n > 64 rows, a short last chunk (1000 =
// 15 x 64 + 40), and fewer rows than columns (one GEQRT, R a trapezoid). Entries N(0, 1): R and
// Q [R; 0] carry Householder's backward error, a small multiple of m eps ||A|| <= m eps sqrt(m n)
// (~1e-11 at 1000 x 45; 1e-12 m bounds it with room); Q's orthonormality a small multiple of m eps.
TEST(HouseholderQr, RowChunksFactorAsGeqrfDoes) {
  const int chunkRows = 64;
  for (const auto& [m, n] : {std::pair<int, int>{50, 45}, {1000, 45}, {130, 100}, {30, 45}, {64, 64}}) {
    SCOPED_TRACE(std::to_string(m) + " x " + std::to_string(n));
    std::vector<double> a(static_cast<size_t>(m) * n);
    std::mt19937 gen(31u + m);
    std::normal_distribution<double> nd;
    for (double& x : a) x = nd(gen);
    const HouseholderQr qr(m, n, a, chunkRows);
    const int k = std::min(m, n);
    ASSERT_EQ(qr.k(), k);
    EXPECT_EQ(qr.chunks(), m <= n ? 1 : 1 + (m - std::min(m, std::max(chunkRows, n)) + chunkRows - 1) / chunkRows);
    const std::vector<double> R = qr.r();
    for (int j = 0; j < n; ++j)
      for (int i = j + 1; i < k; ++i) EXPECT_EQ(R[i + static_cast<size_t>(k) * j], 0.0);
    EXPECT_LT(rowSignDiff(R, geqrfR(m, n, a), k, n), 1e-12 * m);
    EXPECT_LT(orthonormalityError(qr.applyQ(identity(k), k), m, k), 1e-12 * m);
    EXPECT_LT(maxAbsDiff(qr.applyQ(R, n), a), 1e-12 * m);
    // Into a leading dimension above m (a MultiVector's padded storage): the same numbers.
    const int ldo = m + 3;
    std::vector<double> out(static_cast<size_t>(ldo) * n, -7.0), direct = qr.applyQ(R, n);
    qr.applyQInto(R, n, out.data(), ldo);
    double e = 0.0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < m; ++i) e = std::max(e, std::abs(out[i + static_cast<size_t>(ldo) * j] - direct[i + static_cast<size_t>(m) * j]));
    EXPECT_EQ(e, 0.0);
  }
}

TEST(HouseholderQr, RefusesAnArrayShorterThanTheBlock) {
  EXPECT_THROW(HouseholderQr(10, 4, std::vector<double>(39)), InputError);
  EXPECT_THROW(HouseholderQr(10, 4, std::vector<double>(40), 0), InputError);
}

TEST(PivotedCholesky, GivesAnOrthonormalBasisInColumnPivotedQrOrder) {
  const int m = 300, n = 60;
  const DenseMatrix U = randomColumns(m, n, 1e-2, 11u);
  const PivotedCholesky pc = pivotedCholeskyInverse(gram(U));
  ASSERT_EQ(pc.rank, n);
  // Q = U Pi R^{-1}: orthonormal columns.
  DenseMatrix T(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) T(pc.perm[i], j) = pc.Rinv(i, j);
  DenseMatrix Q(m, n);
  Q.multiply(Teuchos::NO_TRANS, Teuchos::NO_TRANS, 1.0, U, T, 0.0);
  DenseMatrix I(n, n);
  for (int i = 0; i < n; ++i) I(i, i) = 1.0;
  EXPECT_LT(maxAbsDiff(gram(Q), I), 1e-10);
  // The pivots of GEQP3 on U.
  DenseMatrix a(U);
  std::vector<int> jpvt(n, 0);
  std::vector<double> tau(n), work(1);
  int info = 0;
  Teuchos::LAPACK<int, double> lapack;
  lapack.GEQP3(m, n, a.values(), a.stride(), jpvt.data(), tau.data(), work.data(), -1, nullptr, &info);
  work.resize(static_cast<size_t>(work[0]));
  lapack.GEQP3(m, n, a.values(), a.stride(), jpvt.data(), tau.data(), work.data(), static_cast<int>(work.size()),
               nullptr, &info);
  ASSERT_EQ(info, 0);
  for (int i = 0; i < n; ++i) EXPECT_EQ(pc.perm[i], jpvt[i] - 1) << "pivot " << i;
  bool identity = true;
  for (int i = 0; i < n; ++i) identity = identity && pc.perm[i] == i;
  EXPECT_FALSE(identity) << "the shuffled scales should make the pivot order non-trivial";
}

TEST(PivotedCholesky, RankDeficientGramMatrixReportsItsRank) {
  const int m = 50, n = 8;
  DenseMatrix U = randomColumns(m, n, 1.0, 5u);
  for (int i = 0; i < m; ++i) U(i, 5) = U(i, 1) - 2.0 * U(i, 3), U(i, 7) = 0.5 * U(i, 0);  // rank 6
  EXPECT_EQ(pivotedCholeskyInverse(gram(U)).rank, 6);
}
