// The run status (RunStatus.hpp) on recorded histories whose outcome is known exactly: which step
// first leaves the full model's range, by which bound, and that a value equal to a bound is still
// within it. These are the status rules `gphr run` applies to every model; the end-to-end case
// (cli_unbounded) only checks that a blown-up run is never `ok`, since at which step a chaotic
// trajectory blows up depends on the last bits of the BLAS kernels the CPU selects.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "gphr/core/RunStatus.hpp"

using gphr::firstUnboundedStep;
using gphr::kUnboundedHamiltonian;
using gphr::kUnboundedNorm;
using gphr::runStatus;
using gphr::statusName;

namespace {

// A history of `steps` + 1 values equal to `base`, with history[from..] = `value`.
std::vector<double> history(long steps, double base, long from = -1, double value = 0.0) {
  std::vector<double> h(steps + 1, base);
  for (long j = from; from >= 0 && j <= steps; ++j) h[j] = value;
  return h;
}

// H0 = -2.5 and a full model of largest norm 3: the bounds are |dH| > 2500 and ||y|| > 300. The
// values are dyadic (exact in binary), so "equal to the bound" is exact, not up to rounding.
constexpr double H0 = -2.5, fomMax = 3.0;
const double hBound = kUnboundedHamiltonian * 2.5, nBound = kUnboundedNorm * fomMax;

TEST(RunStatus, WithinRangeIsOkAtTheBoundsThemselves) {
  // |dH| equal to its bound on both sides of H0, and ||y|| equal to its bound: still within range.
  auto H = history(50, H0, 10, H0 + hBound);
  H[30] = H0 - hBound;
  const auto u = firstUnboundedStep(H0, fomMax, H, history(50, 1.0, 20, nBound));
  EXPECT_EQ(u.step, -1);
  EXPECT_TRUE(u.reason.empty()) << u.reason;
  EXPECT_STREQ(statusName(runStatus(true, true, u.step)), "ok");
}

TEST(RunStatus, HamiltonianBoundGivesTheFirstStepPastIt) {
  // The relative H error crosses 1e3 at step 37 (and stays past it), the norm never does.
  const double past = H0 + std::nextafter(hBound, 2 * hBound);
  auto H = history(100, H0, 37, past);
  H[12] = H0 + hBound;  // equal to the bound earlier: not yet
  const auto u = firstUnboundedStep(H0, fomMax, H, history(100, 2.0));
  EXPECT_EQ(u.step, 37);
  EXPECT_NE(u.reason.find("|H(y0 + A z^j) - H(y^0)| / |H(y^0)| = 1000"), std::string::npos) << u.reason;
  EXPECT_NE(u.reason.find("> 1000"), std::string::npos) << u.reason;
  EXPECT_STREQ(statusName(runStatus(true, true, u.step)), "unbounded");
}

TEST(RunStatus, NormBoundGivesTheFirstStepPastIt) {
  // The lift's norm passes 100 x the full model's largest at step 5; H stays exact.
  const auto u = firstUnboundedStep(H0, fomMax, history(20, H0), history(20, 1.0, 5, 301.0));
  EXPECT_EQ(u.step, 5);
  EXPECT_NE(u.reason.find("||y0 + A z^j|| = 301 > 100 x the full model's largest ||y|| = 3"), std::string::npos)
      << u.reason;
}

TEST(RunStatus, EarlierBoundWinsAndStepZeroCounts) {
  // Norm past at 8, H past at 9: step 8, by the norm. Both past at step 0: step 0, by H.
  auto u = firstUnboundedStep(H0, fomMax, history(20, H0, 9, 1e6), history(20, 1.0, 8, 1e6));
  EXPECT_EQ(u.step, 8);
  EXPECT_NE(u.reason.find("||y0 + A z^j||"), std::string::npos) << u.reason;
  u = firstUnboundedStep(H0, fomMax, history(20, H0, 0, 1e6), history(20, 1.0, 0, 1e6));
  EXPECT_EQ(u.step, 0);
  EXPECT_NE(u.reason.find("|H(y0 + A z^j)"), std::string::npos) << u.reason;
}

TEST(RunStatus, ZeroInitialHamiltonianUsesTheNormBoundAlone) {
  // H(y^0) = 0 gives no relative H bound: any H is within range, only the norm decides.
  EXPECT_EQ(firstUnboundedStep(0.0, fomMax, history(10, 0.0, 1, 1e30), history(10, 1.0)).step, -1);
  EXPECT_EQ(firstUnboundedStep(0.0, fomMax, history(10, 0.0, 1, 1e30), history(10, 1.0, 4, 1e3)).step, 4);
}

TEST(RunStatus, InfiniteValuesAreUnboundedAndHistoriesAreComparedUpToTheShorter) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(firstUnboundedStep(H0, fomMax, history(10, H0, 6, inf), history(10, 1.0)).step, 6);
  // the norm history ends at step 3, before H leaves the range at step 6: nothing is read past it
  EXPECT_EQ(firstUnboundedStep(H0, fomMax, history(10, H0, 6, 1e9), history(3, 1.0)).step, -1);
  EXPECT_EQ(firstUnboundedStep(H0, fomMax, {}, {}).step, -1);
}

TEST(RunStatus, StatusWords) {
  EXPECT_STREQ(statusName(runStatus(true, true, -1)), "ok");
  EXPECT_STREQ(statusName(runStatus(true, true, 0)), "unbounded");
  EXPECT_STREQ(statusName(runStatus(false, true, -1)), "diverged");
  EXPECT_STREQ(statusName(runStatus(false, true, 3)), "diverged");  // a failed run is diverged whatever came before
  EXPECT_STREQ(statusName(runStatus(false, false, -1)), "unavailable");
}

}  // namespace
