// StreamingPod's step routes (podRoute), tested against mathematics on 1, 2 and 3 ranks.
// The data is X = F diag(s) G^T with F (d x R) and G (N x R) orthonormal DCT-II columns, so its
// singular values are exactly s and its leading left singular vectors are exactly F's columns.
// Tolerances (sigma_1 = 1): every step is a backward-stable SVD (Householder/TSQR QR + GESVD,
// GEQRF per rank + GESDD of the stacked R factors + ORMQR, or GESVD of the gathered matrix), so it is the exact SVD of a matrix within ~ nc eps ||Y|| of its
// input (nc <= 42 columns here: ~1e-14 per step, a dozen steps). Weyl's theorem moves the
// singular values by at most that: 1e-12 leaves two orders of headroom. Wedin's theorem moves the
// kept subspace by that over the gap to the dropped singular values (>= 0.25 without truncation:
// ~1e-13); between routes the tolerance is 1e-10, three orders above the measured
// differences (printed by the tests) and far below any real defect (a wrong vector moves it by ~1).
// The subspace distance ||U_a - U_b U_b^T U_a||_F = ||sin Theta||_F is formed directly: from the
// cosines (singular values of U_b^T U_a) it could not resolve angles below sqrt(eps) ~ 1e-8.
#include <gtest/gtest.h>

#include <Teuchos_LAPACK.hpp>

#include <malloc.h>
#include <sys/resource.h>

#include <cmath>
#include <string>
#include <vector>

#include "ReductionTestUtils.hpp"
#include "gphr/core/Error.hpp"
#include "gphr/reduction/StreamingPod.hpp"

using namespace gphr;

namespace {
// Every route forms U from Householder QR factors and SVD vectors: orthonormal to a few eps
// (measured at most 3.0e-15 on 1 to 3 ranks); a column left scaled by its sigma or unnormalized
// is off by O(1). 1e-13 leaves a factor 30.
constexpr double kOrthTol = 1e-13;

// Column j of the orthonormal DCT-II basis of R^size, entry i.
double dct(GO i, int j, GO size) {
  const double pi = std::acos(-1.0);
  return std::sqrt((j == 0 ? 1.0 : 2.0) / static_cast<double>(size)) *
         std::cos(pi * (static_cast<double>(i) + 0.5) * j / static_cast<double>(size));
}

// X = F diag(s) G^T on map (d rows), N columns: singular values s, left vectors F(:, j).
MultiVector knownSvdData(const RCP<const Map>& map, int N, const std::vector<double>& s) {
  const GO d = static_cast<GO>(map->getGlobalNumElements());
  MultiVector X(map, N);
  auto x = X.getLocalViewHost(Tpetra::Access::OverwriteAll);
  for (LO l = 0; l < static_cast<LO>(map->getNodeNumElements()); ++l) {
    const GO i = map->getGlobalElement(l);
    for (int c = 0; c < N; ++c) {
      double v = 0.0;
      for (size_t j = 0; j < s.size(); ++j) v += s[j] * dct(i, static_cast<int>(j), d) * dct(c, static_cast<int>(j), N);
      x(l, c) = v;
    }
  }
  return X;
}

MultiVector leadingDct(const RCP<const Map>& map, int R) {
  const GO d = static_cast<GO>(map->getGlobalNumElements());
  MultiVector F(map, R);
  auto f = F.getLocalViewHost(Tpetra::Access::OverwriteAll);
  for (LO l = 0; l < static_cast<LO>(map->getNodeNumElements()); ++l)
    for (int j = 0; j < R; ++j) f(l, j) = dct(map->getGlobalElement(l), j, d);
  return F;
}

std::vector<double> linearSpectrum(int R, double slope) {
  std::vector<double> s(R);
  for (int j = 0; j < R; ++j) s[j] = 1.0 - j * slope;
  return s;
}

StreamingPod podOf(const MultiVector& X, int maxRank, int blockColumns, PodRoute route, double tol = 1e-8) {
  StreamingPod pod(X.getMap(), maxRank, blockColumns, tol, route);
  pod.add(X);
  return pod;
}

// The incremental SVD of X (d x N, column-major, on one rank) written out densely: per block of
// blockColumns columns, the thin SVD of [U diag(sigma), X_b] by LAPACK GESVD, truncated to the
// leading maxRank values above tol sigma_1 (StreamingPod's rule). U (d x r, column-major) and sigma.
void denseIncrementalSvd(const std::vector<double>& X, int d, int N, int maxRank, int blockColumns, double tol,
                         std::vector<double>& U, std::vector<double>& sigma) {
  Teuchos::LAPACK<int, double> lapack;
  U.clear(), sigma.clear();
  for (int c0 = 0; c0 < N; c0 += blockColumns) {
    const int r = static_cast<int>(sigma.size()), nb = std::min(blockColumns, N - c0), nc = r + nb, k = std::min(d, nc);
    std::vector<double> Y(static_cast<size_t>(d) * nc), S(k), W(static_cast<size_t>(d) * k), work(1);
    for (int j = 0; j < r; ++j)
      for (int i = 0; i < d; ++i) Y[i + static_cast<size_t>(d) * j] = U[i + static_cast<size_t>(d) * j] * sigma[j];
    std::copy_n(X.begin() + static_cast<size_t>(d) * c0, static_cast<size_t>(d) * nb, Y.begin() + static_cast<size_t>(d) * r);
    int info = 0;
    double dummy = 0.0;
    lapack.GESVD('S', 'N', d, nc, Y.data(), d, S.data(), W.data(), d, &dummy, 1, work.data(), -1, nullptr, &info);
    work.resize(static_cast<size_t>(work[0]));
    lapack.GESVD('S', 'N', d, nc, Y.data(), d, S.data(), W.data(), d, &dummy, 1, work.data(),
                 static_cast<int>(work.size()), nullptr, &info);
    EXPECT_EQ(info, 0);
    int keep = 0;
    while (keep < std::min(k, maxRank) && S[keep] > tol * S[0]) ++keep;
    sigma.assign(S.begin(), S.begin() + keep);
    U.assign(W.begin(), W.begin() + static_cast<size_t>(d) * keep);
  }
}

double maxSigmaDiff(const std::vector<double>& a, const std::vector<double>& b) {
  double worst = 0.0;
  for (size_t j = 0; j < std::min(a.size(), b.size()); ++j) worst = std::max(worst, std::abs(a[j] - b[j]));
  return worst;
}

class Routes : public ::testing::Test {
 protected:
  // 128 rows: 64 per rank on 2 ranks, enough for TSQR at up to 64 columns.
  RCP<const Map> map_ = rcp(new Map(128, 0, test::comm()));
};

// Nothing of the data is truncated (maxRank 40 > rank 30): each route must give the exact SVD.
TEST_F(Routes, EachRouteGivesTheExactSvd) {
  const auto s = linearSpectrum(30, 1.0 / 40.0);  // 1 .. 0.275
  const MultiVector X = knownSvdData(map_, 60, s);
  const MultiVector F = leadingDct(map_, 30);
  for (PodRoute route : {PodRoute::Tsqr, PodRoute::Stacked, PodRoute::Tree, PodRoute::Replicated}) {
    const StreamingPod pod = podOf(X, 40, 12, route);  // 5 steps of 12 columns, up to 42 columns
    const char* name = route == PodRoute::Tsqr      ? "tsqr"
                       : route == PodRoute::Stacked ? "stacked"
                       : route == PodRoute::Tree    ? "tree"
                                                    : "replicated";
    SCOPED_TRACE(name);
    EXPECT_EQ(pod.steps().tsqr, route == PodRoute::Tsqr ? 5 : 0);
    EXPECT_EQ(pod.steps().stacked, route == PodRoute::Stacked ? 5 : 0);
    EXPECT_EQ(pod.steps().tree, route == PodRoute::Tree ? 5 : 0);
    EXPECT_EQ(pod.steps().replicated, route == PodRoute::Replicated ? 5 : 0);
    ASSERT_EQ(pod.rank(), 30);
    EXPECT_LE(maxSigmaDiff(pod.singularValues(), s), 1e-12);
    const double dist = test::subspaceDistance(pod.leftVectors(), F);
    EXPECT_LE(dist, 1e-10);
    const double orth = test::orthonormalityError(pod.leftVectors());
    EXPECT_LE(orth, kOrthTol);
    if (test::comm()->getRank() == 0) std::printf("  %s: ||sin Theta(U, F)||_F = %.1e, |U^T U - I| = %.1e\n", name, dist, orth);
  }
}

// Truncation between steps (maxRank 16 < rank 48): the incremental SVD, no longer the exact one,
// but the same on both routes (they truncate at the same places). Each truncation keeps the best
// rank-r part of Y, so B B^T <= X X^T for the carried B = U diag(sigma) (Loewner order, by
// induction over the steps): sigma_j <= s_j on either route. And each route is the recursion
// itself, computed densely on rank 0.
TEST_F(Routes, AllRoutesAgreeUnderTruncation) {
  const auto s = linearSpectrum(48, 1.0 / 64.0);
  const MultiVector X = knownSvdData(map_, 96, s);
  const StreamingPod tsqr = podOf(X, 16, 8, PodRoute::Tsqr);  // 12 steps, truncating from the 3rd
  const StreamingPod repl = podOf(X, 16, 8, PodRoute::Replicated);
  const StreamingPod stacked = podOf(X, 16, 8, PodRoute::Stacked);
  const StreamingPod tree = podOf(X, 16, 8, PodRoute::Tree);
  EXPECT_EQ(tree.steps().tree, 12);
  EXPECT_EQ(tsqr.steps().tsqr, 12);
  EXPECT_EQ(repl.steps().replicated, 12);
  EXPECT_EQ(stacked.steps().stacked, 12);
  ASSERT_EQ(tsqr.rank(), 16);
  ASSERT_EQ(repl.rank(), 16);
  ASSERT_EQ(stacked.rank(), 16);
  ASSERT_EQ(tree.rank(), 16);
  for (const StreamingPod* pod : {&tsqr, &repl, &stacked, &tree})
    for (int j = 0; j < 16; ++j) EXPECT_LE(pod->singularValues()[j], s[j] + 1e-12) << "sigma_" << j;
  const double dSigma = maxSigmaDiff(tsqr.singularValues(), repl.singularValues());
  const double dU = test::subspaceDistance(tsqr.leftVectors(), repl.leftVectors());
  EXPECT_LE(dSigma, 1e-10);
  EXPECT_LE(dU, 1e-10);
  const double dSigmaStacked = maxSigmaDiff(stacked.singularValues(), repl.singularValues());
  const double dUStacked = test::subspaceDistance(stacked.leftVectors(), repl.leftVectors());
  EXPECT_LE(dSigmaStacked, 1e-10);
  EXPECT_LE(dUStacked, 1e-10);
  double orth = 0.0;
  for (const StreamingPod* pod : {&tsqr, &repl, &stacked, &tree}) orth = std::max(orth, test::orthonormalityError(pod->leftVectors()));
  EXPECT_LE(orth, kOrthTol);
  // Against the same recursion computed densely on rank 0 (GESVD per step): a truncation or carry
  // shared by the three routes, which their agreement cannot see, shows here. The routes and the
  // reference are backward-stable SVDs of the same steps; the 16th and 17th values of each step
  // are apart by 1/64 of sigma_1, so the kept subspace is well conditioned: 1e-10 as above.
  const int d = static_cast<int>(X.getGlobalLength());
  const std::vector<double> Xall = test::gatherColumns(X);
  std::vector<std::vector<double>> Us;
  const std::vector<const StreamingPod*> pods = {&tsqr, &repl, &stacked, &tree};
  for (const StreamingPod* pod : pods) Us.push_back(test::gatherColumns(pod->leftVectors()));
  if (test::comm()->getRank() == 0) {
    std::vector<double> Uref, sref;
    denseIncrementalSvd(Xall, d, 96, 16, 8, 1e-8, Uref, sref);
    ASSERT_EQ(sref.size(), 16u);
    for (size_t p = 0; p < Us.size(); ++p) {
      const StreamingPod* pod = pods[p];
      EXPECT_LE(maxSigmaDiff(pod->singularValues(), sref), 1e-10) << "route " << p;
      // ||U_ref - U U^T U_ref||_F, both orthonormal d x 16 (column-major)
      double dist2 = 0.0;
      for (int j = 0; j < 16; ++j) {
        std::vector<double> res(Uref.begin() + static_cast<size_t>(d) * j, Uref.begin() + static_cast<size_t>(d) * (j + 1));
        for (int l = 0; l < 16; ++l) {
          double c = 0.0;
          for (int i = 0; i < d; ++i) c += Us[p][i + static_cast<size_t>(d) * l] * Uref[i + static_cast<size_t>(d) * j];
          for (int i = 0; i < d; ++i) res[i] -= c * Us[p][i + static_cast<size_t>(d) * l];
        }
        for (double x : res) dist2 += x * x;
      }
      EXPECT_LE(std::sqrt(dist2), 1e-10) << "route " << p;
      std::printf("  route %zu vs the dense recursion: ||sin Theta||_F = %.1e\n", p, std::sqrt(dist2));
    }
  }
  if (test::comm()->getRank() == 0) {
    std::printf("  tsqr vs replicated: max |d sigma| = %.1e, ||sin Theta||_F = %.1e\n", dSigma, dU);
    std::printf("  stacked vs replicated: max |d sigma| = %.1e, ||sin Theta||_F = %.1e\n", dSigmaStacked, dUStacked);
    std::printf("  max |U^T U - I| over the routes = %.1e\n", orth);
  }
}

// A POD stopped after some blocks and restored into a fresh one (a checkpoint, as the DEIM stage
// keeps its root's) goes on bit for bit: the next blocks see the same U, sigma and counts, so
// every later step is the same arithmetic. Exact equality is the claim, so no tolerance.
TEST_F(Routes, RestoredStateGoesOnBitForBit) {
  const MultiVector X = knownSvdData(map_, 96, linearSpectrum(48, 1.0 / 64.0));
  const auto first = X.subView(Teuchos::Range1D(0, 39)), rest = X.subView(Teuchos::Range1D(40, 95));
  for (PodRoute route : {PodRoute::Replicated, PodRoute::Stacked, PodRoute::Tree}) {
    StreamingPod whole(map_, 16, 8, 1e-8, route), stopped(map_, 16, 8, 1e-8, route), resumed(map_, 16, 8, 1e-8, route);
    whole.add(*first), whole.add(*rest);
    stopped.add(*first);
    resumed.restore(stopped.state());
    resumed.add(*rest);
    ASSERT_EQ(resumed.rank(), whole.rank());
    EXPECT_EQ(resumed.singularValues(), whole.singularValues());
    EXPECT_EQ(resumed.totalEnergy(), whole.totalEnergy());
    EXPECT_EQ(resumed.columnsAdded(), 96);
    EXPECT_EQ(resumed.steps().stacked + resumed.steps().tree + resumed.steps().replicated, 12);
    const auto a = whole.leftVectors().getLocalViewHost(Tpetra::Access::ReadOnly);
    const auto b = resumed.leftVectors().getLocalViewHost(Tpetra::Access::ReadOnly);
    long differ = 0;
    for (size_t i = 0; i < a.extent(0); ++i)
      for (size_t j = 0; j < a.extent(1); ++j) differ += a(i, j) != b(i, j);
    EXPECT_EQ(differ, 0) << "entries of U that differ";
  }
  // A state that is no POD's: rejected, naming the value.
  StreamingPod pod(map_, 16, 8);
  pod.add(*first);
  StreamingPod::State bad = pod.state();
  std::swap(bad.sigma[0], bad.sigma[1]);
  try {
    StreamingPod(map_, 16, 8).restore(bad);
    FAIL() << "a state with increasing singular values was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("singular value 2"), std::string::npos) << e.what();
  }
  bad = pod.state();
  try {
    StreamingPod(map_, 8, 8).restore(bad);  // 16 values for a maxRank of 8
    FAIL() << "a state above maxRank was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("maxRank = 8"), std::string::npos) << e.what();
  }
}

// 10 rows on every rank; steps of 6 columns: the first (6) fits, the second (6 carried + 6 new)
// does not. 'tsqr' refuses it naming the numbers; 'auto' takes both by the stacked route and
// agrees with 'replicated'.
class TooFewRows : public ::testing::Test {
 protected:
  RCP<const Map> map_ = rcp(new Map(10 * test::comm()->getSize(), 0, test::comm()));
  std::vector<double> s_ = linearSpectrum(8, 0.1);
  MultiVector X_ = knownSvdData(map_, 12, s_);
};

TEST_F(TooFewRows, TsqrRefusesNamingColumnsAndRows) {
  const int P = test::comm()->getSize();
  try {
    podOf(X_, 8, 6, PodRoute::Tsqr);
    FAIL() << "podRoute tsqr took a step of 12 columns on 10 rows per rank";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    for (const std::string& part : {std::string("podRoute 'tsqr'"), std::string("a step of 12 columns (6 carried + 6 new)"),
                                    "on " + std::to_string(P) + " rank(s) the smallest holds 10 of the " +
                                        std::to_string(10 * P) + " rows",
                                    std::string("'auto', 'stacked', 'tree' or 'replicated'")})
      EXPECT_NE(msg.find(part), std::string::npos) << "message lacks '" << part << "': " << msg;
  }
}

// auto: the stacked route on one rank, the tree from 2 (stepRoute); either takes the steps TSQR refuses.
TEST_F(TooFewRows, AutoTakesTheStackedOrTreeRouteAndAgreesWithReplicated) {
  const StreamingPod autoPod = podOf(X_, 8, 6, PodRoute::Auto);
  const StreamingPod repl = podOf(X_, 8, 6, PodRoute::Replicated);
  const bool tree = test::comm()->getSize() >= kTreeRouteFromRanks;
  EXPECT_EQ(autoPod.steps().stacked, tree ? 0 : 2);
  EXPECT_EQ(autoPod.steps().tree, tree ? 2 : 0);
  EXPECT_EQ(autoPod.steps().tsqr + autoPod.steps().replicated, 0);
  ASSERT_EQ(autoPod.rank(), 8);
  ASSERT_EQ(repl.rank(), 8);
  // 12 columns of rank 8 in two steps, maxRank 8: nothing truncated, the exact SVD on both.
  EXPECT_LE(maxSigmaDiff(autoPod.singularValues(), s_), 1e-12);
  EXPECT_LE(maxSigmaDiff(repl.singularValues(), s_), 1e-12);
  EXPECT_LE(test::subspaceDistance(autoPod.leftVectors(), repl.leftVectors()), 1e-10);
  EXPECT_LE(test::orthonormalityError(autoPod.leftVectors()), kOrthTol);
  EXPECT_LE(test::orthonormalityError(repl.leftVectors()), kOrthTol);
}

// Uneven rows: rank 0 holds 40, every other rank 3, fewer than a step's 12 columns (the case
// TSQR refuses). The stacked and tree routes take every step there: rank q's R factor is 3 x 12
// (trapezoidal); the stack has 40 + 3 (P - 1) rows, the tree's stacks 12 + 3 or 3 + 3. 12 columns
// of rank 8 in two steps, maxRank 8: nothing truncated, so each must give the exact SVD
// (tolerances as above).
TEST(StackedAndTreeRoutes, TakeRanksWithFewerRowsThanColumns) {
  const auto comm = test::comm();
  const size_t mine = comm->getRank() == 0 ? 40 : 3;
  const GO d = 40 + 3 * (comm->getSize() - 1);
  const RCP<const Map> map = rcp(new Map(d, mine, 0, comm));
  const auto s = linearSpectrum(8, 0.1);
  const MultiVector X = knownSvdData(map, 12, s);
  for (PodRoute route : {PodRoute::Stacked, PodRoute::Tree}) {
    SCOPED_TRACE(route == PodRoute::Stacked ? "stacked" : "tree");
    const StreamingPod pod = podOf(X, 8, 6, route);
    EXPECT_EQ(pod.steps().stacked + pod.steps().tree, 2);
    ASSERT_EQ(pod.rank(), 8);
    EXPECT_LE(maxSigmaDiff(pod.singularValues(), s), 1e-12);
    EXPECT_LE(test::subspaceDistance(pod.leftVectors(), leadingDct(map, 8)), 1e-10);
    EXPECT_LE(test::orthonormalityError(pod.leftVectors()), kOrthTol);
  }
}

// ||Ua Ua^T - Ub Ub^T||_F of the leading r columns of two d-row column-major bases, formed
// entry by entry (exact to round-off, no cosines: see the file's head).
double projectorDistance(const std::vector<double>& Ua, const std::vector<double>& Ub, int d, int r) {
  double sum = 0.0;
  for (int i = 0; i < d; ++i)
    for (int l = 0; l < d; ++l) {
      double e = 0.0;
      for (int j = 0; j < r; ++j)
        e += Ua[i + static_cast<size_t>(d) * j] * Ua[l + static_cast<size_t>(d) * j] -
             Ub[i + static_cast<size_t>(d) * j] * Ub[l + static_cast<size_t>(d) * j];
      sum += e * e;
    }
  return std::sqrt(sum);
}

// A graded spectrum s_j = 10^(-14 j / 29), j = 0..29: from sigma_1 = 1 down to 1e-14 sigma_1, the
// range the POD meets when the basis is taken to round-off. The tree route (5 steps of 12 columns,
// rankTolerance 0, maxRank 30: only round-off values beyond the 30th are dropped) against one
// dense LAPACK SVD (GESVD) of the gathered matrix on rank 0. Singular values: both are backward
// stable SVDs of the same matrix within ~ nc eps ||X|| (nc <= 42, a few steps), so by Weyl every
// sigma_j of either is within ~1e-14 absolute of the exact one: 1e-12 as in the tests above, now
// also for the values near 1e-14 (a lost tree level moves them by O(1)). Subspace: the leading 5
// vectors (s_5 = 3.9e-3, gap to s_6 2.6e-3): Wedin bounds the move by ~1e-14 / 2.6e-3 ~ 4e-12 per
// side, 1e-10 leaves a factor 10. The same test on 1, 2 and 3 ranks (3: a tree level without a
// partner) checks each against the same dense reference, so the ranks agree to round-off.
TEST(TreeRoute, MatchesTheDenseSvdOnAGradedSpectrum) {
  const RCP<const Map> map = rcp(new Map(128, 0, test::comm()));
  std::vector<double> s(30);
  for (int j = 0; j < 30; ++j) s[j] = std::pow(10.0, -14.0 * j / 29.0);
  const MultiVector X = knownSvdData(map, 60, s);
  const StreamingPod tree = podOf(X, 30, 12, PodRoute::Tree, 0.0);
  EXPECT_EQ(tree.steps().tree, 5);
  ASSERT_EQ(tree.rank(), 30);
  EXPECT_LE(test::orthonormalityError(tree.leftVectors()), kOrthTol);
  const std::vector<double> Xall = test::gatherColumns(X), Utree = test::gatherColumns(tree.leftVectors());
  if (test::comm()->getRank() != 0) return;
  std::vector<double> Udense, sdense;
  denseIncrementalSvd(Xall, 128, 60, 60, 60, 0.0, Udense, sdense);  // one step: the dense thin SVD
  ASSERT_GE(sdense.size(), 30u);
  sdense.resize(30);
  const double dSigma = maxSigmaDiff(tree.singularValues(), sdense), dExact = maxSigmaDiff(tree.singularValues(), s);
  const double dU = projectorDistance(Utree, Udense, 128, 5);
  EXPECT_LE(dSigma, 1e-12);
  EXPECT_LE(dExact, 1e-12);
  EXPECT_LE(dU, 1e-10);
  std::printf("  tree vs dense GESVD (graded to 1e-14): max |d sigma| = %.1e (vs exact %.1e), sigma_30 = %.3e vs %.3e, "
              "||P_tree - P_dense||_F (5 vectors) = %.1e\n", dSigma, dExact, tree.singularValues()[29], sdense[29], dU);
}

// ||X||_F^2 and each column's squared norm against their exact values: X = F diag(s) G^T with
// orthonormal F, so column c's squared norm is sum_j s_j^2 G(c, j)^2 and the whole sum_j s_j^2.
// Each is a sum of d (or N) positive terms, exact to ~d eps relative (d = 301 here): 1e-13. A
// subview of scattered columns (not of constant stride) gives the same numbers bit for bit. The
// POD's total energy is the same sum over the blocks it was given.
TEST(StreamingPod, ColumnNormsAndEnergyAreExact) {
  const auto comm = test::comm();
  const RCP<const Map> map = rcp(new Map(301, 0, comm));
  const int N = 12;
  const auto s = linearSpectrum(8, 0.1);
  const MultiVector X = knownSvdData(map, N, s);
  const std::vector<double> norms = columnSquaredNorms(X);
  ASSERT_EQ(norms.size(), static_cast<size_t>(N));
  double total = 0.0;
  for (int c = 0; c < N; ++c) {
    double exact = 0.0;
    for (size_t j = 0; j < s.size(); ++j) exact += s[j] * s[j] * dct(c, static_cast<int>(j), N) * dct(c, static_cast<int>(j), N);
    EXPECT_NEAR(norms[c], exact, 1e-13 * exact) << "column " << c;
    total += exact;
  }
  const std::vector<size_t> picked = {1, 4, 9};
  const std::vector<double> sub = columnSquaredNorms(*X.subView(Teuchos::ArrayView<const size_t>(picked)));
  for (size_t i = 0; i < picked.size(); ++i) EXPECT_EQ(sub[i], norms[picked[i]]);
  const StreamingPod pod = podOf(X, 8, 5, PodRoute::Auto);
  EXPECT_NEAR(pod.totalEnergy(), total, 1e-13 * total);
}

// A step reuses the previous step's arrays (the leaf's rows x c array and U's storage) instead of
// allocating them anew: fresh arrays cost their pages' faults and the kernel's zeroing every step
// (~10 % of the SWE 256^2 DEIM basis). glibc hands arrays above its mmap threshold (at most
// 32 MB by default, e.g. that DEIM basis' 121 MB leaf array) straight from the kernel and back on
// free; the test fixes the threshold at 256 kB, process-wide (only the binary's speed changes),
// so that its 8 MB arrays behave alike on any rank count. Measured: the minor page faults of 6
// steps after the rank saturates, against the 2048 pages of one step's leaf array (16384 rows x
// 64 columns). Reallocating faults every page of it and of U (3072 a step); reusing leaves the
// MPI library's and the small factors' (measured 25-34 a step on 1-3 ranks; 3100 with both
// array allocated anew each step): a bound of a tenth of the leaf array.
TEST(StreamingPod, StepsReuseTheirArrays) {
  ASSERT_EQ(mallopt(M_MMAP_THRESHOLD, 256 * 1024), 1);
  const auto comm = test::comm();
  const LO rows = 16384;
  const RCP<const Map> map = rcp(new Map(static_cast<GO>(rows) * comm->getSize(), rows, 0, comm));
  MultiVector X(map, 32);
  X.randomize();
  StreamingPod pod(map, 32, 32, -1.0);  // auto route: stacked on 1 rank, the tree from 2
  pod.add(X);
  pod.add(X);  // the rank is 32: every further step takes 32 carried + 32 new columns
  ASSERT_EQ(pod.rank(), 32);
  rusage before{}, after{};
  getrusage(RUSAGE_SELF, &before);
  const int steps = 6;
  for (int i = 0; i < steps; ++i) pod.add(X);
  getrusage(RUSAGE_SELF, &after);
  const double perStep = static_cast<double>(after.ru_minflt - before.ru_minflt) / steps;
  const double arrayPages = static_cast<double>(rows) * 64 * sizeof(double) / 4096;
  EXPECT_LT(perStep, 0.1 * arrayPages) << "minor page faults per step; one step's leaf array has " << arrayPages
                                       << " pages";
  EXPECT_LE(test::orthonormalityError(pod.leftVectors()), kOrthTol);  // and the steps still right
}

TEST(PodRoute, NamesAndUnknownName) {
  EXPECT_EQ(podRouteFromName("auto"), PodRoute::Auto);
  EXPECT_EQ(podRouteFromName("tsqr"), PodRoute::Tsqr);
  EXPECT_EQ(podRouteFromName("stacked"), PodRoute::Stacked);
  EXPECT_EQ(podRouteFromName("tree"), PodRoute::Tree);
  // auto: stacked on one rank (the same work as the tree there), the tree from 2 ranks on.
  EXPECT_EQ(kTreeRouteFromRanks, 2);
  EXPECT_EQ(stepRoute(PodRoute::Auto, 1), PodRoute::Stacked);
  EXPECT_EQ(stepRoute(PodRoute::Auto, 2), PodRoute::Tree);
  EXPECT_EQ(stepRoute(PodRoute::Auto, 3), PodRoute::Tree);
  EXPECT_EQ(stepRoute(PodRoute::Replicated, 64), PodRoute::Replicated);
  EXPECT_EQ(podRouteFromName("replicated"), PodRoute::Replicated);
  try {
    podRouteFromName("anasazi");
    FAIL() << "an unknown route was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'anasazi' is not one of 'auto', 'tsqr', 'stacked', 'tree', 'replicated'"), std::string::npos) << e.what();
  }
}

}  // namespace
