// GP-ADEIM gives the same trajectory, update ranks, sampling and interpolation rows on any rank
// count: the whole chain (training, basis, the first delta0 full-model steps, their POD, every
// update with its resampling over all d rows) runs on all ranks and, on rank 0, on a serial
// sub-communicator; the two are compared. Registered on 2 and 3 ranks only.
#include <gtest/gtest.h>

#include "AdeimTestUtils.hpp"

using namespace gphr;

namespace {

struct Result {
  std::vector<DenseVector> z;
  std::vector<int> ranks;
  std::vector<GO> P, S;
};

Result run(const RCP<const Comm>& c, const std::string& rule) {
  auto hc = test::nlsCase(40, 3, c);
  const int m = 5;
  const double dt = 0.05;
  auto U0 = initialAdeimBasis(hc.test.system, *hc.test.y0, *hc.basis.A, test::denseIntegrator("avf"), dt, 5, m);
  GpAdeimModel model(hc.test.system, hc.basis.A, *U0, m, reduceLinearPart(*hc.test.system, *hc.basis.A),
                     test::adeimOptions(5, 5, 10, 20, rule));
  Result r;
  r.z = test::adaptiveTrajectory(model, "avf", dt, 100).z;
  for (const auto& u : model.updates()) r.ranks.push_back(u.rank);
  r.P = model.interpolationRows();
  r.S = model.samplingRows();
  return r;
}

TEST(GpAdeimRanks, SameTrajectoryAndRowsAsSerial) {
  ASSERT_GT(test::comm()->getSize(), 1) << "register this test on 2 or more ranks";
  for (const std::string rule : {"projected", "residual", "random"}) {
    const Result parallel = run(test::comm(), rule);
    auto serial = test::serialComm();
    if (serial.is_null()) continue;  // ranks > 0 took part in the parallel run only
    const Result ref = run(serial, rule);
    ASSERT_EQ(parallel.z.size(), 101u) << rule;
    ASSERT_EQ(ref.z.size(), parallel.z.size()) << rule;
    EXPECT_EQ(parallel.ranks, ref.ranks) << rule;
    EXPECT_EQ(parallel.P, ref.P) << rule;
    EXPECT_EQ(parallel.S, ref.S) << rule;
    // Bases, POD and weights (sums over rows) agree to round-off across rank counts, each update
    // is a smooth function of them: 1e-10 relative leaves four orders above that.
    EXPECT_LE(test::maxRelDiff(parallel.z, ref.z), 1e-10) << rule;
    EXPECT_GT(*std::max_element(ref.ranks.begin(), ref.ranks.end()), 0) << rule << ": no update ran";
  }
}

}  // namespace
