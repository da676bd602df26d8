// The rank-r update on distributed sampling rows (each rank holding some rows of S^T U and S^T F,
// as GP-ADEIM runs it) equals the serial update of all the rows, on random dense data generated
// identically on every rank. Registered on 2 and 3 ranks only.
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>
#include <cmath>
#include <limits>
#include <random>

#include "gphr/core/Error.hpp"
#include "gphr/hyper/AdeimUpdate.hpp"

namespace gphr {
namespace {

using Teuchos::NO_TRANS;
using Teuchos::TRANS;

constexpr int kM = 8, kMs = 23;

DenseMatrix randomMatrix(int r, int c, std::mt19937& gen) {
  std::normal_distribution<double> N(0.0, 1.0);
  DenseMatrix A(r, c);
  for (int j = 0; j < c; ++j)
    for (int i = 0; i < r; ++i) A(i, j) = N(gen);
  return A;
}

struct Window {
  DenseMatrix PtU, PtF, StU, StF;
};

// repeats > 0: the last `repeats` columns of F copy the first ones, so C has rank wbar - repeats
// < min(m, wbar) and the coefficient factor cuts (the tau_r test then reads the assembled X C^T).
Window randomWindow(int wbar, int repeats, unsigned seed) {
  std::mt19937 gen(seed);
  Window w{randomMatrix(kM, kM, gen), randomMatrix(kM, wbar, gen), randomMatrix(kMs, kM, gen),
           randomMatrix(kMs, wbar, gen)};
  for (int i = 0; i < kM; ++i) w.PtU(i, i) += 4.0;  // a well-conditioned interpolation matrix
  for (int j = wbar - repeats; j < wbar; ++j) {
    for (int i = 0; i < kM; ++i) w.PtF(i, j) = w.PtF(i, j - (wbar - repeats));
    for (int i = 0; i < kMs; ++i) w.StF(i, j) = w.StF(i, j - (wbar - repeats));
  }
  return w;
}

// The rank of row i of S: an interleaved, non-contiguous share. 5 is coprime to 2 and 3, the rank
// counts this test is registered on, so every rank holds rows (with 3 i + 1, as before, rank 1
// held all of them on 3 ranks).
int ownerOf(int i, int np) { return (5 * i + 1) % np; }

// This rank's rows of S; fails the test when it holds none (nothing distributed would be tested).
SampledRowShare share(const Teuchos::RCP<const Teuchos::Comm<int>>& comm) {
  SampledRowShare s;
  s.comm = comm;
  s.numRows = kMs;
  for (int i = 0; i < kMs; ++i)
    if (ownerOf(i, comm->getSize()) == comm->getRank()) s.positions.push_back(i);
  EXPECT_FALSE(s.positions.empty()) << "rank " << comm->getRank() << " holds no row of S";
  return s;
}

DenseMatrix ownRows(const DenseMatrix& A, const SampledRowShare& s) {
  DenseMatrix B(static_cast<int>(s.positions.size()), A.numCols());
  for (int j = 0; j < A.numCols(); ++j)
    for (int i = 0; i < B.numRows(); ++i) B(i, j) = A(s.positions[i], j);
  return B;
}

double relDiff(const DenseMatrix& A, const DenseMatrix& B) {
  DenseMatrix D(A);
  D -= B;
  return D.normFrobenius() / std::max(B.normFrobenius(), 1e-300);
}

DenseMatrix correction(const AdeimUpdate& up) {  // a b^T: the change of S^T U (sign-free)
  DenseMatrix D(up.a.numRows(), up.b.numRows());
  if (up.rank > 0) D.multiply(NO_TRANS, TRANS, 1.0, up.a, up.b, 0.0);
  return D;
}

// The same numbers as the serial update: the distributed one assembles M = S^T R Q_1 exactly (one
// rank contributes each row) and then runs the serial dense algebra, so the only differences are
// the round-off of GEMMs over fewer rows; with singular values of these random data separated by
// more than 1e-2 sigma_1 (the smallest gap in these cases, printed once: 1.04e-2 sigma_1), the SVD's
// vectors move by ~eps / gap < 1e-13: 1e-12 relative leaves margin.
TEST(AdeimUpdateRanks, DistributedRowsGiveTheSerialUpdate) {
  auto comm = Tpetra::getDefaultComm();
  ASSERT_GT(comm->getSize(), 1) << "register this test on 2 or more ranks";
  const SampledRowShare s = share(comm);
  struct Case {
    int wbar, repeats, rank;
    double rankTol;  // 0.3: the tau_r test keeps only some of the m directions of these data
  };
  for (const Case c :
       {Case{12, 0, 0, 1e-8}, Case{12, 0, 0, 0.3}, Case{12, 0, 3, 1e-8}, Case{10, 5, 0, 1e-8}, Case{10, 5, 0, 0.3}}) {
    const Window w = randomWindow(c.wbar, c.repeats, 11 + c.wbar + c.repeats + c.rank);
    AdeimUpdateOptions o;
    o.rank = c.rank;
    o.rankTol = c.rankTol;
    const CoefficientFactor f = factorCoefficients(w.PtU, w.PtF, o.coefficientTol);
    ASSERT_EQ(f.cut, c.repeats > 0);
    const AdeimUpdate ref = computeAdeimUpdate(f, w.StU, w.StF, o);
    const AdeimUpdate up = computeAdeimUpdate(f, ownRows(w.StU, s), ownRows(w.StF, s), o, s);
    const std::string what = "wbar " + std::to_string(c.wbar) + ", rank " + std::to_string(c.rank) + ", rankTol " +
                             std::to_string(c.rankTol);
    ASSERT_GT(ref.rank, 0) << what;
    if (c.rankTol > 0.1) {
      ASSERT_LT(ref.rank, ref.coefficientRank) << what << ": the tolerance should bind";
    }
    EXPECT_EQ(up.rank, ref.rank) << what;
    EXPECT_EQ(up.coefficientRank, ref.coefficientRank) << what;
    EXPECT_NEAR(up.residualBefore, ref.residualBefore, 1e-12 * ref.residualBefore) << what;
    EXPECT_NEAR(up.residualAfter, ref.residualAfter, 1e-12 * ref.residualBefore) << what;
    EXPECT_LE(relDiff(correction(up), correction(ref)), 1e-12) << what;
    DenseMatrix all(w.StU), mine = ownRows(w.StU, s);
    applyAdeimUpdate(ref, all);
    applyAdeimUpdate(up, s, mine);
    EXPECT_LE(relDiff(mine, ownRows(all, s)), 1e-12) << what;
  }
}

// A non-finite entry on one rank's rows is an InputError on every rank (decided after the
// reduction), not an exception on one rank while the others wait in the collective.
TEST(AdeimUpdateRanks, NonFiniteRowOnOneRankThrowsOnAll) {
  auto comm = Tpetra::getDefaultComm();
  ASSERT_GT(comm->getSize(), 1) << "register this test on 2 or more ranks";
  const SampledRowShare s = share(comm);
  Window w = randomWindow(12, 0, 5);
  int owner = -1;
  for (int i = 0; i < kMs && owner < 0; ++i)
    if (ownerOf(i, comm->getSize()) == 1) owner = i;  // a row of rank 1
  w.StF(owner, 0) = std::numeric_limits<double>::quiet_NaN();
  const CoefficientFactor f = factorCoefficients(w.PtU, w.PtF, 1e-8);
  EXPECT_THROW(computeAdeimUpdate(f, ownRows(w.StU, s), ownRows(w.StF, s), AdeimUpdateOptions(), s), InputError);
}

// Inconsistent inputs on one rank (a sampling-row position outside 0 .. m_s - 1) are an
// InputError on every rank, raised after the reduction, not on one rank while the others wait.
TEST(AdeimUpdateRanks, BadPositionOnOneRankThrowsOnAll) {
  auto comm = Tpetra::getDefaultComm();
  ASSERT_GT(comm->getSize(), 1) << "register this test on 2 or more ranks";
  SampledRowShare s = share(comm);
  const Window w = randomWindow(12, 0, 9);
  const DenseMatrix StU = ownRows(w.StU, s), StF = ownRows(w.StF, s);
  if (comm->getRank() == 1) s.positions[0] = kMs;
  const CoefficientFactor f = factorCoefficients(w.PtU, w.PtF, 1e-8);
  EXPECT_THROW(computeAdeimUpdate(f, StU, StF, AdeimUpdateOptions(), s), InputError);
}

}  // namespace
}  // namespace gphr
