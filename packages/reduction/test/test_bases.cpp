// Symplectic bases from distributed snapshots, tested against mathematics:
//  - A^T A = I and A^T J_{2n} A = J_{2k} to 1e-12 (round-off of O(n) sums of O(1) entries);
//  - the singular values equal those of a dense LAPACK SVD of the gathered data matrix
//    (complex Q + iP for psd, real [Q, P] for the cotangent lift);
//  - the basis is the same on 1, 2 and 3 ranks (the phase of each vector is normalised).
#include <gtest/gtest.h>

#include <Teuchos_LAPACK.hpp>
#include <complex>
#include <vector>

#include "ReductionTestUtils.hpp"
#include "gphr/reduction/StreamingPod.hpp"
#include "gphr/reduction/SymplecticBasis.hpp"

using namespace gphr;

namespace {

std::vector<RCP<const MultiVector>> nlsSnapshots(const RCP<const Comm>& comm, GO n) {
  Nls1d scene(n);
  std::vector<RCP<const MultiVector>> out;
  for (double eps : {0.9, 1.1}) out.push_back(test::fomSnapshots(scene.instantiate(comm, {eps}, true), "avf", 0.05, 30));
  return out;
}

double maxAbsDiffFromCanonical(const std::vector<double>& M, int k2, bool symplectic) {
  const int k = k2 / 2;
  double worst = 0.0;
  for (int i = 0; i < k2; ++i)
    for (int j = 0; j < k2; ++j) {
      double ref = 0.0;
      if (!symplectic) ref = (i == j);
      else if (i < k && j == i + k) ref = 1.0;
      else if (i >= k && j == i - k) ref = -1.0;
      worst = std::max(worst, std::abs(M[i * k2 + j] - ref));
    }
  return worst;
}

class Bases : public ::testing::TestWithParam<const char*> {};

TEST_P(Bases, OrthonormalAndSymplectic) {
  const GO n = 48;
  auto snaps = nlsSnapshots(test::comm(), n);
  PhaseSpace ps(n, test::comm());
  BasisOptions opt;
  opt.method = GetParam();
  opt.k = 8;
  opt.blockColumns = 9;  // several incremental steps
  auto basis = computeSymplecticBasis(snaps, ps, opt);
  ASSERT_EQ(basis.A->getNumVectors(), 16u);
  EXPECT_LE(maxAbsDiffFromCanonical(test::transposeTimes(*basis.A, *basis.A), 16, false), 1e-12);
  MultiVector JA(ps.map(), 16);
  ps.applyJ(*basis.A, JA);
  EXPECT_LE(maxAbsDiffFromCanonical(test::transposeTimes(*basis.A, JA), 16, true), 1e-12);
  // These smooth NLS snapshots have fast-decaying singular values: 2k = 16 columns capture
  // 1 - 1.8e-9 (psd) and 1 - 1.7e-6 (cotangent lift) of the energy (measured); a basis built from
  // the wrong singular vectors (the trailing ones, or unsorted) captures far less. 1 - 1e-4 leaves
  // a factor 60 on the worse one.
  EXPECT_GT(basis.energyCaptured, 1.0 - 1e-4);
  if (test::comm()->getRank() == 0) std::printf("  %s: energy captured 1 - %.1e\n", GetParam(), 1.0 - basis.energyCaptured);
  EXPECT_LE(basis.energyCaptured, 1.0 + 1e-12);
  // energyCaptured comes from the singular values alone; the basis must capture it: the snapshots'
  // projected energy sum_s ||A^T y_s||^2 / sum_s ||y_s||^2 equals sum_{j<k} sigma_j^2 / ||C||_F^2
  // exactly when A's columns are the leading singular vectors (psd: |e_j^H (q + ip)|^2 is the sum
  // of the squares on the pair a_j, a_{k+j}; cotangent: blockdiag(Phi, Phi) projects q and p, the
  // columns of [Q, P]). maxRank = 2k + 32 = n truncates nothing, so the identity holds to the
  // round-off of the sums (at most 3.1e-15 measured on 1-3 ranks); the singular vectors taken one
  // index late (e_2 .. e_{k+1}) project 0.011 (psd) and 0.024 (cotangent) of the energy.
  double projected = 0.0, total = 0.0;
  for (const auto& Y : snaps) {
    for (double g : test::transposeTimes(*basis.A, *Y)) projected += g * g;
    for (double s : columnSquaredNorms(*Y)) total += s;
  }
  EXPECT_NEAR(projected / total, basis.energyCaptured, 1e-12);
}

// Singular values against LAPACK on the gathered data (rank 0 only compares). The incremental
// truncation drops triplets below maxRank; with maxRank = 40 of a 48-dof problem whose spectrum
// decays to ~1e-10 of sigma_1, the leading 10 agree to 1e-10 relative to sigma_1.
TEST_P(Bases, SingularValuesMatchDenseSvd) {
  const GO n = 48;
  auto snaps = nlsSnapshots(test::comm(), n);
  PhaseSpace ps(n, test::comm());
  BasisOptions opt;
  opt.method = GetParam();
  opt.k = 10;
  opt.blockColumns = 11;
  opt.maxRank = std::min<int>(40, ps.numLocalDofs() * 1);
  if (test::comm()->getSize() > 1) GTEST_SKIP() << "the dense reference gathers on one rank";
  auto basis = computeSymplecticBasis(snaps, ps, opt);
  const bool psd = std::string(GetParam()) == "psd";
  std::vector<std::complex<double>> C;
  int cols = 0;
  for (const auto& S : snaps) {
    auto all = test::gatherColumns(*S);
    for (size_t j = 0; j < S->getNumVectors(); ++j) {
      const double* y = &all[j * 2 * n];
      if (psd) {
        for (GO i = 0; i < n; ++i) C.emplace_back(y[i], y[n + i]);
        ++cols;
      } else {
        for (GO i = 0; i < n; ++i) C.emplace_back(y[i], 0.0);
        for (GO i = 0; i < n; ++i) C.emplace_back(y[n + i], 0.0);
        cols += 2;
      }
    }
  }
  // Real representation [[Re, -Im], [Im, Re]] (2n x 2cols): each singular value of C twice.
  const int R = 2 * n, Cc = 2 * cols;
  std::vector<double> X(static_cast<size_t>(R) * Cc), sv(std::min(R, Cc)), work(1), dummy(1);
  for (int j = 0; j < cols; ++j)
    for (GO i = 0; i < n; ++i) {
      const auto c = C[j * n + i];
      X[i + R * j] = c.real(), X[n + i + R * j] = c.imag();
      X[i + R * (cols + j)] = -c.imag(), X[n + i + R * (cols + j)] = c.real();
    }
  int info = 0;
  Teuchos::LAPACK<int, double> lapack;
  lapack.GESVD('N', 'N', R, Cc, X.data(), R, sv.data(), dummy.data(), 1, dummy.data(), 1, work.data(), -1, nullptr, &info);
  work.resize(static_cast<size_t>(work[0]));
  lapack.GESVD('N', 'N', R, Cc, X.data(), R, sv.data(), dummy.data(), 1, dummy.data(), 1, work.data(),
               static_cast<int>(work.size()), nullptr, &info);
  ASSERT_EQ(info, 0);
  std::vector<double> s;
  for (size_t j = 0; j < sv.size(); j += 2) s.push_back(sv[j]);
  for (int j = 0; j < 10; ++j) EXPECT_NEAR(basis.singularValues[j], s[j], 1e-10 * s[0]) << "sigma_" << j;
}

// Same basis on P ranks as on one (rank 0 compares). Singular vectors of well-separated
// singular values are determined to ~ eps / gap; with gaps >= 1e-3 sigma_1 here, 1e-9 is safe.
// On one rank the "distributed" run would be the serial one itself: nothing to compare.
TEST_P(Bases, SameOnAnyRankCount) {
  if (test::comm()->getSize() == 1) GTEST_SKIP() << "compares P > 1 ranks with one; run with mpirun -np 2 or 3";
  const GO n = 48;
  BasisOptions opt;
  opt.method = GetParam();
  opt.k = 6;
  opt.blockColumns = 7;
  opt.maxRank = 20;
  PhaseSpace ps(n, test::comm());
  auto dist = test::gatherColumns(*computeSymplecticBasis(nlsSnapshots(test::comm(), n), ps, opt).A);
  auto serial = test::serialComm();
  if (serial.is_null()) return;
  PhaseSpace ps1(n, serial);
  auto ref = test::gatherColumns(*computeSymplecticBasis(nlsSnapshots(serial, n), ps1, opt).A);
  ASSERT_EQ(dist.size(), ref.size());
  double worst = 0.0;
  for (size_t i = 0; i < ref.size(); ++i) worst = std::max(worst, std::abs(dist[i] - ref[i]));
  EXPECT_LE(worst, 1e-9);
}

// reduction.podRoute: TSQR, the stacked and the replicated route give the same basis (the phase is
// normalised, so entrywise; 1e-9 as above: round-off over gaps >= 1e-3 sigma_1), and each run
// takes the route it was given. maxRank 8 and blockColumns 4 fit TSQR on up to 3 ranks (psd:
// 16 + 8 real columns on 32 rows per rank; cotangent: 8 + 8 on 16). A 'tsqr' run whose steps do
// not fit (62 new columns per step against 96 rows at most) is refused.
TEST_P(Bases, SameOnEitherPodRoute) {
  const GO n = 48;
  PhaseSpace ps(n, test::comm());
  const auto snaps = nlsSnapshots(test::comm(), n);
  BasisOptions opt;
  opt.method = GetParam();
  opt.k = 4;
  opt.blockColumns = 4;
  opt.maxRank = 8;
  opt.podRoute = "tsqr";
  const ReducedBasis tsqr = computeSymplecticBasis(snaps, ps, opt);
  opt.podRoute = "replicated";
  const ReducedBasis repl = computeSymplecticBasis(snaps, ps, opt);
  opt.podRoute = "stacked";
  const ReducedBasis stacked = computeSymplecticBasis(snaps, ps, opt);
  EXPECT_GT(tsqr.podSteps.tsqr, 0);
  EXPECT_EQ(tsqr.podSteps.replicated + tsqr.podSteps.stacked, 0);
  EXPECT_EQ(repl.podSteps.tsqr + repl.podSteps.stacked, 0);
  EXPECT_EQ(repl.podSteps.replicated, tsqr.podSteps.tsqr);
  EXPECT_EQ(stacked.podSteps.tsqr + stacked.podSteps.replicated, 0);
  EXPECT_EQ(stacked.podSteps.stacked, tsqr.podSteps.tsqr);
  const auto b = test::gatherColumns(*repl.A);
  for (const ReducedBasis* other : {&tsqr, &stacked}) {
    const auto a = test::gatherColumns(*other->A);
    ASSERT_EQ(a.size(), b.size());
    double worst = 0.0;
    for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
    EXPECT_LE(worst, 1e-9) << (other == &tsqr ? "tsqr" : "stacked") << " against replicated";
  }
  opt.podRoute = "tsqr";
  opt.blockColumns = 60;
  opt.maxRank = 0;
  try {
    computeSymplecticBasis(snaps, ps, opt);
    FAIL() << "podRoute tsqr took steps wider than the rows per rank";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("podRoute 'tsqr' cannot take a step"), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, Bases, ::testing::Values("psd", "cotangent"));

TEST(Bases, RejectsUnknownMethodAndUnavailableSize) {
  PhaseSpace ps(16, test::comm());
  // 3 states of an (unshifted) NLS run: linearly independent over C, so the psd data matrix
  // Q + iP has exactly 3 non-zero singular values.
  auto snaps = test::fomSnapshots(Nls1d(16).instantiate(test::comm(), {1.0}, false), "avf", 0.05, 2);
  BasisOptions opt;
  opt.method = "pod";
  EXPECT_THROW(computeSymplecticBasis({snaps}, ps, opt), InputError);
  // k = 3 is available, k = 4 is not.
  opt.method = "psd";
  opt.k = 3;
  EXPECT_EQ(computeSymplecticBasis({snaps}, ps, opt).A->getNumVectors(), 6u);
  opt.k = 4;
  try {
    computeSymplecticBasis({snaps}, ps, opt);
    FAIL() << "k = 4 from 3 snapshots did not throw";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("k = 4 is not available"), std::string::npos) << msg;
    EXPECT_NE(msg.find("3 singular vectors"), std::string::npos) << msg;
  }
}

}  // namespace
