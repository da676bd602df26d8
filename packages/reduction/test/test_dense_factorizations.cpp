// The small dense factorizations behind GP-ADEIM, tested against exact identities and against
// LAPACK's own column-pivoted QR (GEQP3):
// - denseQrFactorR (blocked GEQRT): R^T R = A^T A and R upper triangular, to round-off;
// - pivotedCholeskyInverse (PSTRF + TRTRI) of G = U^T U: U Pi R^{-1} has orthonormal columns,
//   the pivots are GEQP3's on U (both take the largest remaining column norm first), and a
//   rank-deficient G reports its rank.
// - TriangleStackQr (TPQRT, the tree TSQR's level): Q [R; 0] reproduces the stacked triangles, Q's
//   columns are orthonormal, and R equals GEQRF's of the dense stack up to the signs of its rows;
//   with a trapezoid or nothing below.
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
    const HouseholderQr dense(m, n, stack);
    ASSERT_EQ(qr.rows(), m);
    ASSERT_EQ(qr.k(), n);
    const std::vector<double> R = qr.r(), Rd = dense.r();
    double rowSign = 0.0, orth = 0.0, recon = 0.0;
    for (int i = 0; i < n; ++i) {  // R = diag(+-1) R_geqrf
      const double sign = (R[i + static_cast<size_t>(n) * i] > 0) == (Rd[i + static_cast<size_t>(n) * i] > 0) ? 1.0 : -1.0;
      for (int j = 0; j < n; ++j)
        rowSign = std::max(rowSign, std::abs(R[i + static_cast<size_t>(n) * j] - sign * Rd[i + static_cast<size_t>(n) * j]));
    }
    std::vector<double> I(static_cast<size_t>(n) * n, 0.0);
    for (int i = 0; i < n; ++i) I[i + static_cast<size_t>(n) * i] = 1.0;
    const std::vector<double> Q = qr.applyQ(I, n), QR = qr.applyQ(R, n);  // Q [I; 0], Q [R; 0]
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) {
        double dot = 0.0;
        for (int i = 0; i < m; ++i) dot += Q[i + static_cast<size_t>(m) * a] * Q[i + static_cast<size_t>(m) * b];
        orth = std::max(orth, std::abs(dot - (a == b ? 1.0 : 0.0)));
      }
    for (size_t e = 0; e < stack.size(); ++e) recon = std::max(recon, std::abs(QR[e] - stack[e]));
    EXPECT_LT(rowSign, 1e-12 * n);
    EXPECT_LT(orth, 1e-12);
    EXPECT_LT(recon, 1e-12 * n);
    for (int j = 0; j < n; ++j)
      for (int i = j + 1; i < n; ++i) EXPECT_EQ(R[i + static_cast<size_t>(n) * j], 0.0);
  }
}

TEST(TriangleStackQr, RefusesATrapezoidTallerThanTheTriangle) {
  EXPECT_THROW(TriangleStackQr(3, std::vector<double>(9), 4, std::vector<double>(12)), InputError);
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
