// GP-DEIM gives the same DEIM indices, weights and hyper-reduced trajectory on any rank count:
// the whole offline chain (training, PSD basis, reduced-Jacobian POD, greedy DEIM, weights,
// sample mesh) runs on all ranks and, on rank 0, on a serial sub-communicator; the two are
// compared. Registered on 2 and 3 ranks only: on 1 rank it would compare a run with itself.
#include <gtest/gtest.h>

#include "HyperTestUtils.hpp"

using namespace gphr;

namespace {

struct Result {
  std::vector<GO> indices;
  std::vector<double> weights;
  std::vector<DenseVector> z;
};

Result run(const RCP<const Comm>& c) {
  auto hc = test::nlsCase(40, 3, c);
  const int m = 10;
  Result r;
  r.indices = selectDeimIndices(*hc.deim.U, m);
  r.weights = computeDeimWeights(*hc.deim.U, r.indices, *hc.test.system->nonlinearTerm().weights()).weights;
  auto hr = test::gpDeimModel(hc, m);
  r.z = test::trajectory(*hr, "avf", 0.05, 100);
  return r;
}

TEST(GpDeimRanks, SameIndicesWeightsAndTrajectoryAsSerial) {
  ASSERT_GT(test::comm()->getSize(), 1) << "register this test on 2 or more ranks";
  const Result parallel = run(test::comm());
  auto serial = test::serialComm();
  if (serial.is_null()) return;  // ranks > 0 took part in the parallel run only
  const Result ref = run(serial);
  EXPECT_EQ(parallel.indices, ref.indices);
  // The bases agree to round-off across rank counts (sums in another order); weights and
  // trajectory inherit that: 1e-10 relative leaves four orders of magnitude above it.
  double wmax = 0.0, wdiff = 0.0;
  for (size_t i = 0; i < ref.weights.size(); ++i) {
    wmax = std::max(wmax, std::abs(ref.weights[i]));
    wdiff = std::max(wdiff, std::abs(parallel.weights[i] - ref.weights[i]));
  }
  EXPECT_LE(wdiff, 1e-10 * wmax);
  EXPECT_LE(test::maxRelDiff(parallel.z, ref.z), 1e-10);
}

}  // namespace
