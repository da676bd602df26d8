// gp-eqp gives the same terms, weights and hyper-reduced trajectory on any rank count: the whole
// offline chain (training, PSD basis, the quadrature's training system, greedy NNLS with its
// global argmax) runs on all ranks and, on rank 0, on a serial sub-communicator; the two are
// compared, on the exact rows and on a sketch of them. Registered on 2 and 3 ranks only.
#include <gtest/gtest.h>

#include "HyperTestUtils.hpp"
#include "gphr/hyper/EmpiricalQuadrature.hpp"

using namespace gphr;

namespace {

struct Result {
  QuadratureFit fit;
  std::vector<DenseVector> z;
};

Result run(const RCP<const Comm>& c, int sketchRows) {
  auto hc = test::nlsCase(40, 3, c);
  QuadratureOptions o;
  o.sketchRows = sketchRows;
  Result r;
  r.fit = nnlsQuadrature(buildQuadratureTraining(hc.training, hc.snapshots, *hc.basis.A, o), 10, 0.0);
  auto hr = buildQuadratureModel(*hc.test.system, *hc.basis.A, r.fit, reduceLinearPart(*hc.test.system, *hc.basis.A));
  r.z = test::trajectory(*hr, "avf", 0.05, 100);
  return r;
}

TEST(EqpRanks, SameTermsWeightsAndTrajectoryAsSerial) {
  ASSERT_GT(test::comm()->getSize(), 1) << "register this test on 2 or more ranks";
  for (int sketchRows : {0, 300}) {
    const Result parallel = run(test::comm(), sketchRows);
    auto serial = test::serialComm();
    if (serial.is_null()) continue;  // ranks > 0 took part in the parallel run only
    const Result ref = run(serial, sketchRows);
    EXPECT_EQ(parallel.fit.terms, ref.fit.terms) << "sketch rows " << sketchRows;
    // The bases agree to round-off across rank counts (sums in another order); the columns, the
    // least-squares solves and the trajectory inherit that: 1e-10 relative leaves four orders of
    // magnitude above it (as test_gpdeim_ranks).
    ASSERT_EQ(parallel.fit.weights.size(), ref.fit.weights.size());
    double wmax = 0.0, wdiff = 0.0;
    for (size_t i = 0; i < ref.fit.weights.size(); ++i) {
      wmax = std::max(wmax, std::abs(ref.fit.weights[i]));
      wdiff = std::max(wdiff, std::abs(parallel.fit.weights[i] - ref.fit.weights[i]));
    }
    EXPECT_LE(wdiff, 1e-10 * wmax) << "sketch rows " << sketchRows;
    EXPECT_LE(test::maxRelDiff(parallel.z, ref.z), 1e-10) << "sketch rows " << sketchRows;
    std::printf("[eqp] ranks %d vs 1, sketch rows %d: %zu terms, weights differ by %.2e of max\n",
                test::comm()->getSize(), sketchRows, ref.fit.terms.size(), wdiff / wmax);
  }
}

}  // namespace
