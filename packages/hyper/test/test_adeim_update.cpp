// The rank-r DEIM basis update of GP-ADEIM (paper Sec. 4.1) against its mathematics, on random
// dense data: eq:update_error, Lemma theo:update_error, global minimality, an independent rank-1
// computation (Peherstorfer & Willcox 2015, Lemma 3.5: the generalized eigenproblem solved with
// LAPACK SYGV), scale invariance, and the degenerate cases.
#include <gtest/gtest.h>

#include <Teuchos_LAPACK.hpp>
#include <cmath>
#include <random>

#include "gphr/core/Error.hpp"
#include "gphr/hyper/AdeimSampling.hpp"
#include "gphr/hyper/AdeimUpdate.hpp"

namespace gphr {
namespace {

using Teuchos::NO_TRANS;
using Teuchos::TRANS;

DenseMatrix randomMatrix(int r, int c, std::mt19937& gen, double scale = 1.0) {
  std::normal_distribution<double> N(0.0, scale);
  DenseMatrix A(r, c);
  for (int j = 0; j < c; ++j)
    for (int i = 0; i < r; ++i) A(i, j) = N(gen);
  return A;
}

DenseMatrix mul(Teuchos::ETransp ta, Teuchos::ETransp tb, const DenseMatrix& A, const DenseMatrix& B) {
  DenseMatrix C(ta == NO_TRANS ? A.numRows() : A.numCols(), tb == NO_TRANS ? B.numCols() : B.numRows());
  C.multiply(ta, tb, 1.0, A, B, 0.0);
  return C;
}

double relDiff(const DenseMatrix& A, const DenseMatrix& B) {
  DenseMatrix D(A);
  D -= B;
  return D.normFrobenius() / std::max(B.normFrobenius(), 1e-300);
}

bool finite(const DenseMatrix& A) {
  for (int j = 0; j < A.numCols(); ++j)
    for (int i = 0; i < A.numRows(); ++i)
      if (!std::isfinite(A(i, j))) return false;
  return true;
}

// One update problem: rows P and S of U and of the window F.
struct Window {
  DenseMatrix PtU, PtF, StU, StF;
};

Window randomWindow(int m, int ms, int wbar, unsigned seed) {
  std::mt19937 gen(seed);
  Window w{randomMatrix(m, m, gen), randomMatrix(m, wbar, gen), randomMatrix(ms, m, gen), randomMatrix(ms, wbar, gen)};
  for (int i = 0; i < m; ++i) w.PtU(i, i) += 4.0;  // keep P^T U well conditioned (an interpolation matrix)
  return w;
}

// C_j = (P^T U)^{-1} P^T F solved here with LAPACK GESV, independently of the code's
// deimCoefficients (GETRF + GETRI + GEMM): the references below are built from it, not from the
// update's own C.
DenseMatrix coefficients(const Window& w) {
  DenseMatrix C(w.PtF), lu(w.PtU);
  std::vector<int> piv(lu.numRows());
  int info = 0;
  Teuchos::LAPACK<int, double>().GESV(lu.numRows(), C.numCols(), lu.values(), lu.stride(), piv.data(), C.values(),
                                      C.stride(), &info);
  EXPECT_EQ(info, 0);
  return C;
}

// S^T R = S^T U C - S^T F.
DenseMatrix residual(const Window& w, const DenseMatrix& C) {
  DenseMatrix X = mul(NO_TRANS, NO_TRANS, w.StU, C);
  X -= w.StF;
  return X;
}

// The objective of eq:min_prob, ||S^T R + a b^T C||_F^2.
double objective(const Window& w, const DenseMatrix& C, const DenseMatrix& a, const DenseMatrix& b) {
  DenseMatrix X = residual(w, C);
  if (a.numCols() > 0) X.multiply(NO_TRANS, NO_TRANS, 1.0, a, mul(TRANS, NO_TRANS, b, C), 1.0);
  const double f = X.normFrobenius();
  return f * f;
}

// The pencil (C X^T X C^T, C C^T) of eq:gen_eval, X = S^T R, solved directly with LAPACK SYGV
// (B = C C^T SPD): eigenvalues descending and their B-orthonormal eigenvectors (columns).
void pencilEigen(const DenseMatrix& X, const DenseMatrix& C, std::vector<double>& lambda, DenseMatrix& V) {
  const DenseMatrix XC = mul(NO_TRANS, TRANS, X, C);
  DenseMatrix A = mul(TRANS, NO_TRANS, XC, XC), B = mul(NO_TRANS, TRANS, C, C);
  const int m = A.numRows();
  std::vector<double> ev(m), work(1);
  int info = 0;
  Teuchos::LAPACK<int, double> lapack;
  lapack.SYGV(1, 'V', 'U', m, A.values(), A.stride(), B.values(), B.stride(), ev.data(), work.data(), -1, &info);
  work.resize(static_cast<size_t>(work[0]));
  lapack.SYGV(1, 'V', 'U', m, A.values(), A.stride(), B.values(), B.stride(), ev.data(), work.data(),
              static_cast<int>(work.size()), &info);
  ASSERT_EQ(info, 0);
  lambda.assign(ev.rbegin(), ev.rend());
  V.shape(m, m);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) V(i, j) = A(i, m - 1 - j);
}

// eq:gen_eval for the window's own residual.
void generalizedEigen(const Window& w, const DenseMatrix& C, std::vector<double>& lambda, DenseMatrix& V) {
  pencilEigen(residual(w, C), C, lambda, V);
}

AdeimUpdateOptions rankOptions(int r) {
  AdeimUpdateOptions o;
  o.rank = r;
  return o;
}

constexpr int kM = 6, kMs = 15, kW = 20;

// eq:update_error for every r = 1..m, and the eigenvalues against SYGV. Tolerance 1e-12 relative
// to ||S^T R||^2: both sides are sums of O(m) terms of that size, each exact to a few eps
// (backward-stable SVDs, condition numbers of these random data < 1e2).
// The objective and ||S^T R|| are formed here from C by GESV (cond(P^T U) < 1e2: C to ~1e-14).
TEST(AdeimUpdate, UpdateErrorIdentityForEveryRank) {
  const Window w = randomWindow(kM, kMs, kW, 1);
  const DenseMatrix C = coefficients(w);
  const double before2 = objective(w, C, DenseMatrix(kMs, 0), DenseMatrix(kM, 0));
  for (int r = 1; r <= kM; ++r) {
    const AdeimUpdate up = computeAdeimUpdate(w.PtU, w.PtF, w.StU, w.StF, rankOptions(r));
    ASSERT_EQ(up.rank, r);
    EXPECT_LT(relDiff(up.C, C), 1e-13);
    EXPECT_NEAR(up.residualBefore * up.residualBefore, before2, 1e-12 * before2);
    double sum = 0.0;
    for (int i = 0; i < r; ++i) sum += up.eigenvalues[i];
    const double after2 = objective(w, C, up.a, up.b);
    EXPECT_NEAR(after2, before2 - sum, 1e-12 * before2) << "r = " << r;  // eq:update_error
    EXPECT_NEAR(up.residualAfter * up.residualAfter, after2, 1e-12 * before2) << "r = " << r;  // the reported value
  }
  // The eigenvalues of eq:gen_eval, solved independently on the pencil (SYGV). cond(C C^T) < 1e2
  // here, so SYGV's eigenvalues carry ~1e-14 relative error: 1e-10 leaves margin.
  const AdeimUpdate up = computeAdeimUpdate(w.PtU, w.PtF, w.StU, w.StF, rankOptions(kM));
  std::vector<double> lambda;
  DenseMatrix V;
  generalizedEigen(w, C, lambda, V);
  ASSERT_EQ(up.eigenvalues.size(), lambda.size());
  for (int i = 0; i < kM; ++i) EXPECT_NEAR(up.eigenvalues[i], lambda[i], 1e-10 * lambda[0]) << i;
}

// Lemma theo:update_error: with r = rank(S^T R C^T) the residual at S is S^T R (I - C_bar),
// C_bar = C^T (C C^T)^{-1} C formed here by the normal equations (POSV), independently of the
// SVD route of the code. Tolerance 1e-12 relative to ||S^T R|| (cond(C C^T) < 1e2).
TEST(AdeimUpdate, LemmaResidualIsProjectedResidual) {
  const Window w = randomWindow(kM, kMs, kW, 2);
  AdeimUpdateOptions o;
  o.rankTol = 0.0;  // the full numerical rank r-bar
  const AdeimUpdate up = computeAdeimUpdate(w.PtU, w.PtF, w.StU, w.StF, o);
  ASSERT_EQ(up.rank, kM);
  const DenseMatrix C = coefficients(w);
  DenseMatrix G = mul(NO_TRANS, TRANS, C, C), Y(C);  // Y = (C C^T)^{-1} C
  int info = 0;
  Teuchos::LAPACK<int, double>().POSV('U', kM, kW, G.values(), G.stride(), Y.values(), Y.stride(), &info);
  ASSERT_EQ(info, 0);
  DenseMatrix Cbar = mul(TRANS, NO_TRANS, C, Y), I(kW, kW);
  for (int i = 0; i < kW; ++i) I(i, i) = 1.0;
  I -= Cbar;
  DenseMatrix X = residual(w, C);
  const double expected = mul(NO_TRANS, NO_TRANS, X, I).normFrobenius();
  EXPECT_NEAR(std::sqrt(objective(w, C, up.a, up.b)), expected, 1e-12 * up.residualBefore);
  EXPECT_NEAR(up.residualAfter, expected, 1e-12 * up.residualBefore);
}

// The update is a global minimizer over rank-r pairs: random perturbations of (a, b), small and
// large, never lower the objective (beyond round-off: 1e-13 relative).
TEST(AdeimUpdate, UpdateIsGlobalMinimizer) {
  const Window w = randomWindow(kM, kMs, kW, 3);
  std::mt19937 gen(33);
  const DenseMatrix C = coefficients(w);
  for (int r : {1, 3}) {
    const AdeimUpdate up = computeAdeimUpdate(w.PtU, w.PtF, w.StU, w.StF, rankOptions(r));
    const double best = objective(w, C, up.a, up.b);
    for (double eps : {1e-6, 1e-3, 1e-1, 10.0})
      for (int trial = 0; trial < 50; ++trial) {
        DenseMatrix a(up.a), b(up.b);
        a += randomMatrix(kMs, r, gen, eps * up.a.normFrobenius());
        b += randomMatrix(kM, r, gen, eps * up.b.normFrobenius());
        EXPECT_GE(objective(w, C, a, b), best * (1.0 - 1e-13)) << "r = " << r << ", eps = " << eps;
      }
  }
}

// r = 1 against Peherstorfer & Willcox's rank-one update (their Lemma 3.5), computed here from
// the pencil with SYGV: beta = top eigenvector, alpha = -S^T R C^T beta / ||C^T beta||^2.
// The pair (alpha, beta) is unique up to scaling; U_{j+1} = U_j + alpha beta^T is unique.
// Tolerance 1e-12 relative (well-separated top eigenvalue, cond(C C^T) < 1e2).
TEST(AdeimUpdate, RankOneMatchesPeherstorferLemma35) {
  const Window w = randomWindow(kM, kMs, kW, 4);
  const AdeimUpdate up = computeAdeimUpdate(w.PtU, w.PtF, w.StU, w.StF, rankOptions(1));
  const DenseMatrix C = coefficients(w);  // his C from P^T U and P^T F, not the update's
  std::vector<double> lambda;
  DenseMatrix V;
  generalizedEigen(w, C, lambda, V);
  DenseMatrix beta(kM, 1);
  for (int i = 0; i < kM; ++i) beta(i, 0) = V(i, 0);
  const DenseMatrix Ctb = mul(TRANS, NO_TRANS, C, beta);
  DenseMatrix X = residual(w, C);
  DenseMatrix alpha = mul(NO_TRANS, NO_TRANS, X, Ctb);
  const double n2 = Ctb.normFrobenius() * Ctb.normFrobenius();
  alpha.scale(-1.0 / n2);
  DenseMatrix expected(w.StU), ours(w.StU);
  expected.multiply(NO_TRANS, TRANS, 1.0, alpha, beta, 1.0);
  applyAdeimUpdate(up, ours);
  EXPECT_LT(relDiff(ours, expected), 1e-12);
}

// Scaling F by 1e-8 or 1e+8 scales C and S^T R alike: the rank chosen by tau_r, the updated
// basis U_{j+1} (a b^T is scale-free) and lambda / scale^2 are unchanged (1e-12 relative).
TEST(AdeimUpdate, ScaleOfFChangesNothingButTheScale) {
  const Window w = randomWindow(kM, kMs, kW, 5);
  AdeimUpdateOptions o;
  o.rankTol = 0.5;  // an intermediate rank, so that an absolute test would move it
  const AdeimUpdate ref = computeAdeimUpdate(w.PtU, w.PtF, w.StU, w.StF, o);
  ASSERT_GT(ref.rank, 0);
  ASSERT_LT(ref.rank, kM);
  DenseMatrix Uref(w.StU);
  applyAdeimUpdate(ref, Uref);
  for (double s : {1e-8, 1e8}) {
    DenseMatrix PtF(w.PtF), StF(w.StF);
    PtF.scale(s);
    StF.scale(s);
    const AdeimUpdate up = computeAdeimUpdate(w.PtU, PtF, w.StU, StF, o);
    EXPECT_EQ(up.rank, ref.rank) << "scale " << s;
    DenseMatrix U(w.StU);
    applyAdeimUpdate(up, U);
    EXPECT_LT(relDiff(U, Uref), 1e-12) << "scale " << s;
    EXPECT_NEAR(up.eigenvalues[0] / (s * s), ref.eigenvalues[0], 1e-12 * ref.eigenvalues[0]);
  }
}

// The rank by tau_r is the paper's test, the number of singular values of S^T R C^T above
// tau_r sigma_1, here computed from the product in the test (LAPACK GESVD). Random data have
// singular values apart by far more than round-off, so the counts must agree exactly; tau_r runs
// through every gap. Also with C numerically rank-deficient (a cut), where the rank is capped at
// rank(C) = 5.
TEST(AdeimUpdate, RankTolCountsSingularValuesOfProjectedResidual) {
  for (bool cut : {false, true}) {
    Window w = randomWindow(kM, kMs, kW, cut ? 12 : 11);
    if (cut)  // P^T F's last row a combination of the others: C = (P^T U)^{-1} P^T F has rank 5
      for (int j = 0; j < kW; ++j) w.PtF(kM - 1, j) = 0.5 * w.PtF(0, j) - 0.25 * w.PtF(1, j);
    DenseMatrix C(w.PtF), lu(w.PtU);
    std::vector<int> piv(kM);
    int info = 0;
    Teuchos::LAPACK<int, double> lapack;
    lapack.GESV(kM, kW, lu.values(), lu.stride(), piv.data(), C.values(), C.stride(), &info);
    ASSERT_EQ(info, 0);
    const DenseMatrix X = residual(w, C);
    DenseMatrix XC = mul(NO_TRANS, TRANS, X, C);
    std::vector<double> sv(kM), work(5 * kMs * kM + 100);
    double dummy = 0.0;
    lapack.GESVD('N', 'N', kMs, kM, XC.values(), XC.stride(), sv.data(), &dummy, 1, &dummy, 1, work.data(),
                 static_cast<int>(work.size()), nullptr, &info);
    ASSERT_EQ(info, 0);
    const int rankC = cut ? kM - 1 : kM;
    for (int i = 1; i < kM; ++i) {
      const double tol = std::sqrt(sv[i - 1] * sv[i]) / sv[0];  // between sigma_i and sigma_{i+1}
      AdeimUpdateOptions o;
      o.rankTol = tol;
      const AdeimUpdate up = computeAdeimUpdate(w.PtU, w.PtF, w.StU, w.StF, o);
      EXPECT_EQ(up.coefficientRank, rankC) << "cut " << cut;
      EXPECT_EQ(up.rank, std::min(i, rankC)) << "cut " << cut << ", tau_r " << tol;
    }
  }
}

// Rank-deficient C_j: a window with fewer columns than m (wbar = 4 < m = 6; rank 4, no cut, R12 of
// the pivoted QR non-zero) and one whose columns 5..9 repeat columns 0..4 (rank 5; the pivoted QR
// cuts a round-off R22).
struct DeficientCase {
  const char* name;
  Window w;
  int rank;
};

std::vector<DeficientCase> deficientWindows() {
  Window few = randomWindow(kM, kMs, 4, 6);
  Window rep = randomWindow(kM, kMs, 10, 7);
  for (int j = 5; j < 10; ++j) {
    for (int i = 0; i < kM; ++i) rep.PtF(i, j) = rep.PtF(i, j - 5);
    for (int i = 0; i < kMs; ++i) rep.StF(i, j) = rep.StF(i, j - 5);
  }
  return {{"wbar 4 < m", few, 4}, {"repeated columns", rep, 5}};
}

// An orthonormal basis of range(C) (m x rank) from the left singular vectors of C (LAPACK GESVD),
// independently of the code's pivoted QR of C^T. The ranks here are exact (fewer columns, repeated
// columns), so the singular values past the rank are round-off, cut at 1e-10 sigma_1.
DenseMatrix rangeBasis(const DenseMatrix& C, int expectedRank) {
  const int m = C.numRows(), n = C.numCols(), k = std::min(m, n);
  DenseMatrix A(C), U(m, k);
  std::vector<double> s(k), work(5 * (m + n) + 64);
  double vt = 0.0;
  int info = 0;
  Teuchos::LAPACK<int, double>().GESVD('S', 'N', m, n, A.values(), A.stride(), s.data(), U.values(), U.stride(), &vt,
                                       1, work.data(), static_cast<int>(work.size()), nullptr, &info);
  EXPECT_EQ(info, 0);
  int r = 0;
  while (r < k && s[r] > 1e-10 * s[0]) ++r;
  EXPECT_EQ(r, expectedRank);
  DenseMatrix Q(m, r);
  for (int j = 0; j < r; ++j)
    for (int i = 0; i < m; ++i) Q(i, j) = U(i, j);
  return Q;
}

// X - Q Q^T X: the part of X's columns outside range(Q) (Q orthonormal).
DenseMatrix outside(const DenseMatrix& Q, const DenseMatrix& X) {
  DenseMatrix D(X);
  D.multiply(NO_TRANS, NO_TRANS, -1.0, Q, mul(TRANS, NO_TRANS, Q, X), 1.0);
  return D;
}

// The update on a rank-deficient C runs in C's row space (rank r_C): finite, and it lowers the
// residual, which the objective recomputed here confirms (1e-12 relative to ||S^T R||: the
// identity eq:update_error, sums of O(m) terms each exact to a few eps on these data).
TEST(AdeimUpdate, RankDeficientCoefficients) {
  for (const DeficientCase& c : deficientWindows()) {
    AdeimUpdateOptions o;
    o.rankTol = 0.0;
    AdeimUpdate up;
    ASSERT_NO_THROW(up = computeAdeimUpdate(c.w.PtU, c.w.PtF, c.w.StU, c.w.StF, o)) << c.name;
    EXPECT_EQ(up.coefficientRank, c.rank) << c.name;
    EXPECT_GT(up.rank, 0) << c.name;
    EXPECT_TRUE(finite(up.a) && finite(up.b)) << c.name;
    EXPECT_LT(up.residualAfter, up.residualBefore) << c.name;
    EXPECT_NEAR(std::sqrt(objective(c.w, coefficients(c.w), up.a, up.b)), up.residualAfter,
                1e-12 * up.residualBefore)
        << c.name;
  }
}

// b lies in range(C_j), as the paper's b = Q_j z after theo:minprob_eig_equivalence: its part in
// null(C_j^T) = range(C_j)^perp is round-off. Tolerance 1e-12 ||b||: the basis of range(C) here
// (GESVD) and the code's T^+ (QR of T^T) each carry ~eps cond errors and cond(C) < 1e2 on these
// random data (a few 1e-15 measured); a right inverse of T with a null(C^T) part leaves an O(1)
// fraction of b outside (the figure printed).
TEST(AdeimUpdate, RankDeficientUpdateLiesInRangeOfC) {
  for (const DeficientCase& c : deficientWindows()) {
    const DenseMatrix Q = rangeBasis(coefficients(c.w), c.rank);
    for (int r = 1; r <= c.rank; ++r) {
      const AdeimUpdate up = computeAdeimUpdate(c.w.PtU, c.w.PtF, c.w.StU, c.w.StF, rankOptions(r));
      ASSERT_EQ(up.rank, r) << c.name;
      const double part = outside(Q, up.b).normFrobenius() / up.b.normFrobenius();
      if (r == c.rank) std::printf("%s, r = %d: ||b outside range(C)|| / ||b|| = %.3g\n", c.name, r, part);
      EXPECT_LT(part, 1e-12) << c.name << ", r = " << r;
    }
  }
}

// Of all minimisers of eq:min_prob the update has the least ||a b^T||_F: a part of b in
// null(C_j^T) leaves the objective unchanged (C^T b is the same) and can only add to the norm.
// Checked against b + N Y for random Y (N an orthonormal basis of null(C^T)) and against the
// projection of b onto range(C) (the least-norm minimiser sharing a). Objectives agree to 1e-12
// relative (the same C^T b up to round-off); norms may not drop below ||a b^T|| (1 - 1e-12).
TEST(AdeimUpdate, UpdateHasLeastNormAmongMinimisers) {
  std::mt19937 gen(77);
  for (const DeficientCase& c : deficientWindows()) {
    const DenseMatrix C = coefficients(c.w);
    DenseMatrix I(kM, kM);
    for (int i = 0; i < kM; ++i) I(i, i) = 1.0;
    const DenseMatrix N = rangeBasis(outside(rangeBasis(C, c.rank), I), kM - c.rank);  // of I - Q Q^T: null(C^T)
    for (int r : {1, c.rank}) {
      const AdeimUpdate up = computeAdeimUpdate(c.w.PtU, c.w.PtF, c.w.StU, c.w.StF, rankOptions(r));
      const double best = objective(c.w, C, up.a, up.b);
      const double norm = mul(NO_TRANS, TRANS, up.a, up.b).normFrobenius();
      DenseMatrix projected(up.b);
      projected.multiply(NO_TRANS, NO_TRANS, -1.0, N, mul(TRANS, NO_TRANS, N, up.b), 1.0);
      std::vector<DenseMatrix> others{projected};
      for (int trial = 0; trial < 20; ++trial) {
        DenseMatrix b(up.b);
        b.multiply(NO_TRANS, NO_TRANS, 1.0, N, randomMatrix(kM - c.rank, r, gen, up.b.normFrobenius()), 1.0);
        others.push_back(b);
      }
      for (const DenseMatrix& b : others) {
        EXPECT_NEAR(objective(c.w, C, up.a, b), best, 1e-12 * up.residualBefore * up.residualBefore) << c.name;
        EXPECT_GE(mul(NO_TRANS, TRANS, up.a, b).normFrobenius(), norm * (1.0 - 1e-12)) << c.name << ", r = " << r;
      }
    }
  }
}

// eq:gen_eval restricted to range(C_j) (the paper's route when rank(C_j) < m): with Q an
// orthonormal basis of range(C) (GESVD, here), Z = Q^T C has full row rank; the top r eigenvectors
// z_i of Z X^T X Z^T z = lambda Z Z^T z (LAPACK SYGV), b_i = Q z_i and a_i from eq:ai_from_bi give
// S^T U_{j+1} = S^T U_j + a b^T, which the code's update must reproduce for every r. Tolerance
// 1e-10 relative: cond(Z Z^T) = cond(C)^2 < 1e4 on these random data and the eigenvalue gaps are
// O(1) relative, so SYGV's eigenvectors carry < 1e-12 error (differences measured: printed).
TEST(AdeimUpdate, RankDeficientUpdateMatchesRestrictedEigenproblem) {
  for (const DeficientCase& c : deficientWindows()) {
    const DenseMatrix C = coefficients(c.w), Q = rangeBasis(C, c.rank);
    const DenseMatrix X = residual(c.w, C), Z = mul(TRANS, NO_TRANS, Q, C);  // Z: r_C x wbar
    std::vector<double> lambda;
    DenseMatrix V;
    pencilEigen(X, Z, lambda, V);
    for (int r = 1; r <= c.rank; ++r) {
      DenseMatrix zr(c.rank, r);
      for (int i = 0; i < r; ++i)
        for (int l = 0; l < c.rank; ++l) zr(l, i) = V(l, i);
      const DenseMatrix b = mul(NO_TRANS, NO_TRANS, Q, zr);
      const DenseMatrix Ctb = mul(TRANS, NO_TRANS, C, b);
      DenseMatrix a = mul(NO_TRANS, NO_TRANS, X, Ctb);  // eq:ai_from_bi, column by column
      for (int i = 0; i < r; ++i) {
        double n2 = 0.0;
        for (int l = 0; l < Ctb.numRows(); ++l) n2 += Ctb(l, i) * Ctb(l, i);
        for (int l = 0; l < kMs; ++l) a(l, i) /= -n2;
      }
      DenseMatrix expected(c.w.StU), ours(c.w.StU);
      expected.multiply(NO_TRANS, TRANS, 1.0, a, b, 1.0);
      const AdeimUpdate up = computeAdeimUpdate(c.w.PtU, c.w.PtF, c.w.StU, c.w.StF, rankOptions(r));
      ASSERT_EQ(up.rank, r) << c.name;
      applyAdeimUpdate(up, ours);
      DenseMatrix diff(ours);
      diff -= expected;
      double maxDiff = 0.0;
      for (int j = 0; j < kM; ++j)
        for (int i = 0; i < kMs; ++i) maxDiff = std::max(maxDiff, std::abs(diff(i, j)));
      std::printf("%s, r = %d: |U_{j+1} - restricted|_F / |U_{j+1}|_F = %.3g, max entry %.3g\n", c.name, r,
                  relDiff(ours, expected), maxDiff);
      EXPECT_LT(relDiff(ours, expected), 1e-10) << c.name << ", r = " << r;
    }
  }
}

// C of full rank in exact arithmetic, its last row the first one plus ratio times a random row:
// sigma_min / sigma_1 ~ ratio, cond(C C^T) ~ ratio^-2. (A last row equal to the first times
// 1 + ratio would be parallel to it: rank-deficient in exact arithmetic, not ill-conditioned.)
// At ratio 1e-9 (cond(C C^T) ~ 1e18, past what the Gram matrix resolves) the QR route keeps the
// direction under the default cut (1e-10; for these data |R_66| / |R_11| lies between 5e-10 and
// 1e-9, measured by cutting at those values): the update still lowers the residual, and the
// objective recomputed here from (a, b) matches the reported residual to 1e-6 relative (b
// carries 1 / sigma ~ 1e9, so forming a b^T C here loses ~1e9 eps). At ratio 1e-14 (|R_66| /
// |R_11| between 1e-15 and 1e-14), below the cut, the direction is dropped. No NaN in either case.
TEST(AdeimUpdate, NumericallySingularGramMatrix) {
  for (const auto& [ratio, kept] : {std::pair<double, int>{1e-9, kM}, {1e-14, kM - 1}}) {
    Window w = randomWindow(kM, kMs, kW, 8);
    std::mt19937 gen(88);
    DenseMatrix C = randomMatrix(kM, kW, gen);
    const DenseMatrix E = randomMatrix(1, kW, gen);
    for (int j = 0; j < kW; ++j) C(kM - 1, j) = C(0, j) + ratio * E(0, j);  // last row ~ first row
    w.PtF = mul(NO_TRANS, NO_TRANS, w.PtU, C);
    AdeimUpdateOptions o;
    o.rankTol = 0.0;
    AdeimUpdate up;
    ASSERT_NO_THROW(up = computeAdeimUpdate(w.PtU, w.PtF, w.StU, w.StF, o)) << "ratio " << ratio;
    EXPECT_EQ(up.coefficientRank, kept) << "ratio " << ratio << " with the default coefficientTol";
    EXPECT_TRUE(finite(up.a) && finite(up.b)) << "ratio " << ratio;
    EXPECT_LT(up.residualAfter, up.residualBefore) << "ratio " << ratio;
    EXPECT_NEAR(std::sqrt(objective(w, C, up.a, up.b)), up.residualAfter, 1e-6 * up.residualBefore)
        << "ratio " << ratio;
  }
}

// F in the span of U (the DEIM approximation is exact): residual zero up to round-off, rank 0,
// S^T U unchanged bit for bit. An all-zero window as well (C = 0).
TEST(AdeimUpdate, ZeroResidualIsANoOp) {
  Window w = randomWindow(kM, kMs, kW, 9);
  std::mt19937 gen(99);
  const DenseMatrix C0 = randomMatrix(kM, kW, gen);
  w.PtF = mul(NO_TRANS, NO_TRANS, w.PtU, C0);
  w.StF = mul(NO_TRANS, NO_TRANS, w.StU, C0);
  Window z = w;
  z.PtF.putScalar(0.0);
  z.StF.putScalar(0.0);
  for (const Window* x : {&w, &z}) {
    AdeimUpdate up;
    ASSERT_NO_THROW(up = computeAdeimUpdate(x->PtU, x->PtF, x->StU, x->StF, AdeimUpdateOptions{}));
    EXPECT_EQ(up.rank, 0);
    DenseMatrix U(x->StU);
    applyAdeimUpdate(up, U);
    EXPECT_EQ(relDiff(U, x->StU), 0.0);
  }
}

// The factor of C is a rank-revealing QR of C^T: Q orthonormal, C^T = Q T when nothing is cut,
// T Tinv = I and Tinv T symmetric (Tinv = T^+); with C of rank 5 (P^T F's last row a combination
// of two others) one direction is cut and C^T = Q T still holds to round-off (the cut R22 is
// round-off). Tolerance 1e-13: a few
// hundred eps for Householder QR and a triangular inverse of these well-conditioned (cond < 1e2)
// random factors.
TEST(AdeimUpdate, CoefficientFactorIsARankRevealingQR) {
  for (bool cut : {false, true}) {
    Window w = randomWindow(kM, kMs, kW, cut ? 12 : 11);
    if (cut)
      for (int j = 0; j < kW; ++j) w.PtF(kM - 1, j) = 0.5 * w.PtF(0, j) - 0.25 * w.PtF(1, j);
    const CoefficientFactor f = factorCoefficients(w.PtU, w.PtF, 1e-8);
    const int rc = cut ? kM - 1 : kM;
    ASSERT_EQ(f.rank(), rc);
    EXPECT_EQ(f.cut, cut);
    DenseMatrix I(rc, rc);
    for (int i = 0; i < rc; ++i) I(i, i) = 1.0;
    EXPECT_LT(relDiff(mul(TRANS, NO_TRANS, f.Q, f.Q), I), 1e-13);
    EXPECT_LT(relDiff(mul(NO_TRANS, NO_TRANS, f.T, f.Tinv), I), 1e-13);
    // Tinv is the pseudo-inverse: Tinv T is the orthogonal projector onto range(T^T), symmetric
    // (the Moore-Penrose condition a right inverse with a part in null(T) fails).
    const DenseMatrix P = mul(NO_TRANS, NO_TRANS, f.Tinv, f.T);
    EXPECT_LT(relDiff(P, mul(TRANS, TRANS, f.T, f.Tinv)), 1e-13) << "cut " << cut;
    DenseMatrix Ct(kW, kM);
    for (int j = 0; j < kW; ++j)
      for (int i = 0; i < kM; ++i) Ct(j, i) = f.C(i, j);
    EXPECT_LT(relDiff(mul(NO_TRANS, NO_TRANS, f.Q, f.T), Ct), 1e-13) << "cut " << cut;
  }
}

// The sampling scores of alg:indices_adapt against their definition: the row norms of R C_bar,
// R = U C - F, C_bar = C^T (C C^T)^{-1} C formed by the normal equations (POSV), and of R itself
// for the residual rule. Tolerance 1e-12 relative to the largest row norm of R (cond(C C^T) < 1e2).
TEST(AdeimUpdate, ProjectedScoresAreRowNormsOfRCbar) {
  const int rows = 40;
  const Window w = randomWindow(kM, kMs, kW, 13);
  const CoefficientFactor f = factorCoefficients(w.PtU, w.PtF, 1e-8);
  std::mt19937 gen(131);
  const DenseMatrix U = randomMatrix(rows, kM, gen), F = randomMatrix(rows, kW, gen);
  std::vector<double> Fl(rows * kW);  // row-major; U is read column-major (DenseMatrix storage)
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < kW; ++j) Fl[i * kW + j] = F(i, j);
  DenseMatrix R = mul(NO_TRANS, NO_TRANS, U, f.C);
  R -= F;
  DenseMatrix G = mul(NO_TRANS, TRANS, f.C, f.C), Y(f.C);
  int info = 0;
  Teuchos::LAPACK<int, double>().POSV('U', kM, kW, G.values(), G.stride(), Y.values(), Y.stride(), &info);
  ASSERT_EQ(info, 0);
  const DenseMatrix RCbar = mul(NO_TRANS, NO_TRANS, R, mul(TRANS, NO_TRANS, f.C, Y));
  const std::vector<double> projected = residualRowNorms(U.values(), U.stride(), Fl, rows, f, true);
  const std::vector<double> plain = residualRowNorms(U.values(), U.stride(), Fl, rows, f, false);
  double scale = 0.0;
  for (int i = 0; i < rows; ++i) {
    double a = 0.0;
    for (int j = 0; j < kW; ++j) a += R(i, j) * R(i, j);
    scale = std::max(scale, std::sqrt(a));
  }
  for (int i = 0; i < rows; ++i) {
    double p = 0.0, q = 0.0;
    for (int j = 0; j < kW; ++j) p += RCbar(i, j) * RCbar(i, j), q += R(i, j) * R(i, j);
    EXPECT_NEAR(projected[i], std::sqrt(p), 1e-12 * scale) << "row " << i;
    EXPECT_NEAR(plain[i], std::sqrt(q), 1e-12 * scale) << "row " << i;
  }
}

TEST(AdeimUpdate, SingularInterpolationMatrixIsAClearError) {
  Window w = randomWindow(kM, kMs, kW, 10);
  for (int j = 0; j < kM; ++j) w.PtU(2, j) = 0.0;
  try {
    computeAdeimUpdate(w.PtU, w.PtF, w.StU, w.StF, AdeimUpdateOptions{});
    FAIL() << "a singular P^T U was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("singular"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gphr
