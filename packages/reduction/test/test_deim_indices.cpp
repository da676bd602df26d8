// Greedy DEIM indices, tested against the textbook algorithm (Chaturantabut & Sorensen 2010,
// Alg. 1) written out here on the gathered basis: at step l solve (P^T U_l) c = P^T u_l, form
// r = u_l - U_l c and take argmax |r|. The library computes the same indices by Gaussian
// elimination with partial pivoting on the distributed U; the two agree exactly (the same rows
// win: the residuals differ by round-off only, far below the gaps between the largest entries
// of these smooth-random columns), on 1, 2 and 3 ranks.
#include <gtest/gtest.h>

#include <Teuchos_LAPACK.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "TestUtils.hpp"
#include "gphr/core/Error.hpp"
#include "gphr/core/ReplicatedGather.hpp"
#include "gphr/reduction/Deim.hpp"

using namespace gphr;

namespace {

// Uniform in [-1, 1) from (seed, g, j) by SplitMix64: independent columns, and the same entry
// on any rank count.
double hashed(unsigned seed, GO g, int j) {
  uint64_t x = (static_cast<uint64_t>(seed) << 40) ^ (static_cast<uint64_t>(g) << 12) ^ static_cast<uint64_t>(j);
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  x ^= x >> 31;
  return 2.0 * static_cast<double>(x >> 11) / 9007199254740992.0 - 1.0;
}

RCP<MultiVector> basis(GO d, int m, unsigned seed) {
  auto map = rcp(new Map(d, 0, test::comm()));
  auto U = rcp(new MultiVector(map, m));
  auto u = U->getLocalViewHost(Tpetra::Access::OverwriteAll);
  for (LO i = 0; i < static_cast<LO>(map->getNodeNumElements()); ++i)
    for (int j = 0; j < m; ++j) u(i, j) = hashed(seed, map->getGlobalElement(i), j);
  return U;
}

std::vector<GO> textbookDeim(const MultiVector& U, int m) {
  const GO d = static_cast<GO>(U.getGlobalLength());
  const int nc = static_cast<int>(U.getNumVectors());
  std::vector<GO> all(d);
  for (GO g = 0; g < d; ++g) all[g] = g;
  const std::vector<double> rows = gatherRows(U, all);  // d x nc, row-major
  auto u = [&](GO i, int j) { return rows[static_cast<size_t>(i) * nc + j]; };
  std::vector<GO> P;
  Teuchos::LAPACK<int, double> lapack;
  for (int l = 0; l < m; ++l) {
    std::vector<double> B(static_cast<size_t>(l) * l), c(l);
    for (int i = 0; i < l; ++i) {
      c[i] = u(P[i], l);
      for (int j = 0; j < l; ++j) B[i + static_cast<size_t>(l) * j] = u(P[i], j);
    }
    std::vector<int> piv(l);
    int info = 0;
    if (l > 0) lapack.GESV(l, 1, B.data(), l, piv.data(), c.data(), l, &info);
    EXPECT_EQ(info, 0);
    GO best = -1;
    double bestAbs = -1.0;
    for (GO i = 0; i < d; ++i) {
      double r = u(i, l);
      for (int j = 0; j < l; ++j) r -= u(i, j) * c[j];
      if (std::abs(r) > bestAbs) bestAbs = std::abs(r), best = i;
    }
    P.push_back(best);
  }
  return P;
}

TEST(GreedyDeim, EqualsTheTextbookAlgorithmOnAnyRankCount) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const auto U = basis(97, 20, seed);
    const std::vector<GO> ref = textbookDeim(*U, 20);
    EXPECT_EQ(selectDeimIndices(*U, 20, "deim"), ref) << "seed " << seed;
    // Fewer indices are the leading ones of the same greedy sequence.
    EXPECT_EQ(selectDeimIndices(*U, 7, "deim"), std::vector<GO>(ref.begin(), ref.begin() + 7));
  }
  // Longer greedy sequences: the blocked elimination (panels of 32 columns) must still pick the
  // textbook rows. m = 40: one full panel and a partial one.
  const auto U = basis(131, 40, 5);
  EXPECT_EQ(selectDeimIndices(*U, 40, "deim"), textbookDeim(*U, 40));
  // m = 70: two full panels of 32 columns and a partial one, so the trailing (TRSM + GEMM) update
  // runs twice and meets the last panel's 6 columns.
  const auto V = basis(211, 70, 6);
  EXPECT_EQ(selectDeimIndices(*V, 70, "deim"), textbookDeim(*V, 70));
}

// Q-DEIM (Drmac & Gugercin 2016): the indices are the first m column pivots of a QR with column
// pivoting of U^T (m x d). Written out here as the textbook Businger-Golub pivoting with modified
// Gram-Schmidt on the gathered rows: at step j take the row of U whose part orthogonal to the
// rows taken so far is largest (the first on a tie), then remove that direction from the rest.
// The library's LAPACK GEQP3 (Householder, its norms downdated) picks the same rows: the
// remaining norms differ by round-off only, far below the gaps between the largest of them for
// these random rows; the same on 1, 2 and 3 ranks (the gathered rows are the same).
std::vector<GO> textbookQdeim(const MultiVector& U, int m) {
  const GO d = static_cast<GO>(U.getGlobalLength());
  const int nc = static_cast<int>(U.getNumVectors());
  std::vector<GO> all(d);
  for (GO g = 0; g < d; ++g) all[g] = g;
  std::vector<double> rows = gatherRows(U, all);  // d x nc, row-major: the columns of U^T
  auto row = [&](GO i) { return rows.data() + static_cast<size_t>(i) * nc; };
  std::vector<char> taken(d, 0);
  std::vector<GO> P;
  for (int j = 0; j < m; ++j) {
    GO best = -1;
    double bestNorm = -1.0;
    for (GO i = 0; i < d; ++i) {
      double norm = 0.0;
      for (int a = 0; a < m; ++a) norm += row(i)[a] * row(i)[a];  // U^T's first m rows: U's first m columns
      if (!taken[i] && norm > bestNorm) bestNorm = norm, best = i;
    }
    P.push_back(best);
    taken[best] = 1;
    std::vector<double> q(row(best), row(best) + m);
    const double qn = std::sqrt(bestNorm);
    for (double& x : q) x /= qn;
    for (GO i = 0; i < d; ++i) {
      double dot = 0.0;
      for (int a = 0; a < m; ++a) dot += q[a] * row(i)[a];
      for (int a = 0; a < m; ++a) row(i)[a] -= dot * q[a];
    }
  }
  return P;
}

TEST(Qdeim, EqualsTheTextbookPivotedQrOnAnyRankCount) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const auto U = basis(97, 20, seed);
    const std::vector<GO> P = selectDeimIndices(*U, 20, "qdeim");
    EXPECT_EQ(P, textbookQdeim(*U, 20)) << "seed " << seed;
    std::vector<GO> sorted(P);
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(std::unique(sorted.begin(), sorted.end()), sorted.end()) << "an index twice";
  }
  const auto V = basis(151, 40, 7);
  EXPECT_EQ(selectDeimIndices(*V, 40, "qdeim"), textbookQdeim(*V, 40));
}

// The gather of a row-major array of each rank's own rows (what LocalRows, GP-ADEIM's copy of
// A's rows for its moving sample meshes, gathers through) equals the MultiVector gather of the
// same rows, in any order, on any rank count; an id no rank owns is refused by name.
TEST(ReplicatedGather, RowsOfALocalArrayEqualTheMultiVectorGather) {
  const int nc = 5;
  const auto U = basis(23, nc, 6);
  const Map& map = *U->getMap();
  std::vector<double> local(map.getNodeNumElements() * nc);
  auto u = U->getLocalViewHost(Tpetra::Access::ReadOnly);
  for (size_t i = 0; i < map.getNodeNumElements(); ++i)
    for (int j = 0; j < nc; ++j) local[i * nc + j] = u(i, j);
  const std::vector<GO> gids = {22, 0, 11, 5, 17, 1};
  const std::vector<double> want = gatherRows(*U, gids);
  EXPECT_EQ(gatherRows(map, local, nc, gids), want);
  for (size_t i = 0; i < gids.size(); ++i)  // and the rows are the right ones
    EXPECT_EQ(want[i * nc + 2], hashed(6, gids[i], 2));
  try {
    gatherRows(map, local, nc, {3, 23});
    FAIL() << "row 23 of a 23-row map must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("global id 23"), std::string::npos) << e.what();
  }
}

// ADEIM's partial point update (Peherstorfer & Willcox 2015, Sec. 4.1): index i is re-chosen as
// the greedy step for column i with the others fixed. For the last column of a greedy P that step
// is the greedy algorithm's own last step, so P comes back unchanged; for another column the new
// index is the argmax of the textbook residual, computed here from the gathered basis.
TEST(DeimPointUpdate, IsTheGreedyStepForOneColumn) {
  const int m = 12;
  const auto U = basis(83, m, 5);
  const std::vector<GO> P = selectDeimIndices(*U, m, "deim");
  EXPECT_EQ(replaceDeimIndices(*U, P, {m - 1}), P);
  for (int i : {0, 4, 9}) {
    const std::vector<GO> Q = replaceDeimIndices(*U, P, {i});
    const GO d = static_cast<GO>(U->getGlobalLength());
    std::vector<GO> all(d);
    for (GO g = 0; g < d; ++g) all[g] = g;
    const std::vector<double> rows = gatherRows(*U, all);
    auto u = [&](GO r, int j) { return rows[static_cast<size_t>(r) * m + j]; };
    std::vector<int> others;
    for (int j = 0; j < m; ++j)
      if (j != i) others.push_back(j);
    const int k = m - 1;
    std::vector<double> B(static_cast<size_t>(k) * k), c(k);
    for (int a = 0; a < k; ++a) {
      c[a] = u(P[others[a]], i);
      for (int b = 0; b < k; ++b) B[a + static_cast<size_t>(k) * b] = u(P[others[a]], others[b]);
    }
    std::vector<int> piv(k);
    int info = 0;
    Teuchos::LAPACK<int, double>().GESV(k, 1, B.data(), k, piv.data(), c.data(), k, &info);
    ASSERT_EQ(info, 0);
    GO best = -1;
    double bestAbs = -1.0;
    for (GO r = 0; r < d; ++r) {
      bool fixed = false;
      for (int a : others) fixed = fixed || P[a] == r;
      if (fixed) continue;
      double res = u(r, i);
      for (int b = 0; b < k; ++b) res -= u(r, others[b]) * c[b];
      if (std::abs(res) > bestAbs) bestAbs = std::abs(res), best = r;
    }
    std::vector<GO> want = P;
    want[i] = best;
    EXPECT_EQ(Q, want) << "column " << i;
  }
  EXPECT_THROW(replaceDeimIndices(*U, P, {m}), InputError);
}

// Ties go to the smallest gid: column 0 has |u| = 1 exactly at five rows (on different ranks,
// and in different and equal positions modulo 4, the pivot search's lanes) and |u| < 1 elsewhere,
// so the first index is row 7 on any rank count, and the sequence is the textbook's (which takes
// the first of equal residuals). The same basis on a map whose gids fall with the local index
// (the pivot search's second scan) gives the same gids.
TEST(GreedyDeim, TiesGoToTheSmallestGid) {
  const GO d = 97;
  const int m = 20;
  const std::vector<GO> ones = {90, 41, 11, 7, 8};
  auto fill = [&](MultiVector& U) {
    const Map& map = *U.getMap();
    auto u = U.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (LO i = 0; i < static_cast<LO>(map.getNodeNumElements()); ++i) {
      const GO g = map.getGlobalElement(i);
      for (int j = 0; j < m; ++j) u(i, j) = hashed(9, g, j);
      const bool one = std::find(ones.begin(), ones.end(), g) != ones.end();
      u(i, 0) = one ? (g % 2 ? -1.0 : 1.0) : 0.5 * u(i, 0);
    }
  };
  auto U = rcp(new MultiVector(rcp(new Map(d, 0, test::comm())), m));
  fill(*U);
  const std::vector<GO> P = selectDeimIndices(*U, m, "deim");
  ASSERT_EQ(P.front(), 7);
  EXPECT_EQ(P, textbookDeim(*U, m));
  // The same rows, each rank's gids in falling order.
  const Map& contiguous = *U->getMap();
  std::vector<GO> mine;
  for (LO i = static_cast<LO>(contiguous.getNodeNumElements()) - 1; i >= 0; --i) mine.push_back(contiguous.getGlobalElement(i));
  auto V = rcp(new MultiVector(rcp(new Map(d, Teuchos::ArrayView<const GO>(mine), 0, test::comm())), m));
  fill(*V);
  EXPECT_EQ(selectDeimIndices(*V, m, "deim"), P);
}

TEST(GreedyDeim, RankDeficientBasisIsAClearError) {
  const auto U = basis(50, 6, 4);
  Tpetra::deep_copy(*U->getVectorNonConst(4), *U->getVector(1));  // column 5 repeats column 2
  try {
    selectDeimIndices(*U, 6, "deim");
    FAIL() << "a repeated basis column must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("column 5 vanishes"), std::string::npos) << e.what();
  }
}

// GP-ADEIM's per-update condition number: LAPACK GECON's estimate of cond_1(P^T U) from the LU
// of the weights, against ||B||_1 ||B^{-1}||_1 with B^{-1} formed here (GETRF + GETRI). The
// estimator evaluates ||B^{-1} x||_1 for a unit x, a lower bound up to round-off (1e-12 relative
// slack), and Higham (1988) reports it within a factor 3 in nearly all cases (the bound below).
// The weights solve their defining system (P^T U)^T w = U^T v (residual checked here with B and
// U^T v formed independently: 1e-13 relative, a few eps times cond(B) ~ 10), and are the same
// numbers in both modes (the same LU solve); the exact mode's conditionNumber is cond_2(B) from
// the singular values (GESVD here; 1e-12 relative, both backward-stable SVDs of the same B).
TEST(DeimWeights, ConditionEstimateIsTheOneNormConditionNumber) {
  const int m = 8;
  const auto U = basis(60, m, 5);
  const std::vector<GO> P = selectDeimIndices(*U, m, "deim");
  Vector v(U->getMap());
  v.putScalar(1.0);
  const DeimWeights exact = computeDeimWeights(*U, P, v), est = computeDeimWeights(*U, P, v, true);
  EXPECT_EQ(exact.weights, est.weights);
  const std::vector<double> rows = gatherRows(*U, P);
  std::vector<double> B(m * m);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) B[i + m * j] = rows[i * m + j];
  auto norm1 = [&](const std::vector<double>& A) {
    double n = 0.0;
    for (int j = 0; j < m; ++j) {
      double c = 0.0;
      for (int i = 0; i < m; ++i) c += std::abs(A[i + m * j]);
      n = std::max(n, c);
    }
    return n;
  };
  std::vector<double> inv(B), work(64 * m);
  std::vector<int> piv(m);
  int info = 0;
  Teuchos::LAPACK<int, double> lapack;
  lapack.GETRF(m, m, inv.data(), m, piv.data(), &info);
  ASSERT_EQ(info, 0);
  lapack.GETRI(m, inv.data(), m, piv.data(), work.data(), static_cast<int>(work.size()), &info);
  ASSERT_EQ(info, 0);
  const double cond1 = norm1(B) * norm1(inv);
  EXPECT_LE(est.conditionNumber, cond1 * (1.0 + 1e-12));
  EXPECT_GE(est.conditionNumber, cond1 / 3.0);
  // (P^T U)^T w = U^T v: B^T w - U^T v, U^T v from the columns' dot products.
  ASSERT_EQ(exact.weights.size(), static_cast<size_t>(m));
  double res = 0.0, scale = 0.0;
  for (int j = 0; j < m; ++j) {
    double btw = 0.0;
    for (int i = 0; i < m; ++i) btw += B[i + m * j] * exact.weights[i];
    const double utv = U->getVector(j)->dot(v);
    res = std::max(res, std::abs(btw - utv));
    scale = std::max(scale, std::abs(utv));
  }
  EXPECT_LE(res, 1e-13 * scale);
  std::vector<double> sv(m), Bc(B);
  double dummy = 0.0;
  lapack.GESVD('N', 'N', m, m, Bc.data(), m, sv.data(), &dummy, 1, &dummy, 1, work.data(),
               static_cast<int>(work.size()), nullptr, &info);
  ASSERT_EQ(info, 0);
  EXPECT_NEAR(exact.conditionNumber, sv[0] / sv[m - 1], 1e-12 * sv[0] / sv[m - 1]);
}

}  // namespace
