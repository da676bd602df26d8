// Gauss-Legendre with q points on [0, 1] integrates s^k exactly (to round-off) for k <= 2q - 1
// and not for k = 2q (its error, >= 9e-8 for q <= 6, is far above round-off): the property
// AVF's exact quadrature relies on.
#include <gtest/gtest.h>

#include <cmath>

#include "gphr/core/Error.hpp"
#include "gphr/core/Quadrature.hpp"

using namespace gphr;

TEST(Quadrature, GaussLegendreIsExactToDegree2qMinus1) {
  for (int q = 1; q <= 6; ++q) {
    const auto r = gaussLegendre(q);
    for (int k = 0; k <= 2 * q; ++k) {
      double sum = 0.0;
      for (int i = 0; i < q; ++i) sum += r.weights[i] * std::pow(r.nodes[i], k);
      const double exact = 1.0 / (k + 1);
      if (k <= 2 * q - 1)
        EXPECT_NEAR(sum, exact, 1e-14) << "q = " << q << ", k = " << k;  // a few ulps of O(1) sums
      else
        EXPECT_GT(std::abs(sum - exact), 1e-10) << "q = " << q << " must not be exact for k = " << k;
    }
  }
}

TEST(Quadrature, PointsForDegreeAndMidpoint) {
  EXPECT_EQ(gaussPointsForDegree(4), 2);  // NLS: grad G cubic
  EXPECT_EQ(gaussPointsForDegree(3), 2);  // SWE: grad G quadratic
  EXPECT_EQ(gaussPointsForDegree(2), 1);  // quadratic H: midpoint is exact
  const auto m = gaussLegendre(1);
  EXPECT_DOUBLE_EQ(m.nodes[0], 0.5);
  EXPECT_DOUBLE_EQ(m.weights[0], 1.0);
  EXPECT_THROW(gaussLegendre(0), InputError);
}
