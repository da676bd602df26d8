// The parameter interpolant of the reduced-model file against mathematics: it returns the node
// values exactly at the nodes, reproduces polynomials of degree < N per parameter to round-off,
// and converges geometrically for an analytic function (the SWE's Gaussian-width dependence).
#include <gtest/gtest.h>

#include <cmath>

#include "gphr/core/Error.hpp"
#include "gphr/hyper/ParameterInterpolant.hpp"

using gphr::ParameterInterpolant;

namespace {

// Two values per point: a polynomial of degree 4 in each parameter, and exp(-8 a) b (analytic).
std::vector<double> f(const std::vector<double>& mu) {
  const double a = mu[0], b = mu[1];
  return {1.0 + 2 * a - 3 * b + a * a * b * b * b - 0.5 * std::pow(a, 4) * std::pow(b, 4), std::exp(-8.0 * a) * b};
}

ParameterInterpolant fitted(int nodes) {
  ParameterInterpolant I({{1.1, 1.7}, {0.7, 1.3}}, {nodes, nodes}, 2);
  for (size_t j = 0; j < I.numNodes(); ++j) I.setNodeValues(j, f(I.node(j)));
  return I;
}

// max |I - f| / max |f| over a grid that misses the nodes (the sup-norm relative error).
double worstRelative(const ParameterInterpolant& I, size_t component) {
  double worst = 0.0, scale = 0.0;
  for (double a = 1.1; a <= 1.7; a += 0.0373)
    for (double b = 0.7; b <= 1.3; b += 0.0419) {
      const double exact = f({a, b})[component], got = I.evaluate({a, b})[component];
      worst = std::max(worst, std::abs(got - exact));
      scale = std::max(scale, std::abs(exact));
    }
  return worst / scale;
}

}  // namespace

TEST(ParameterInterpolant, ReturnsTheNodeValuesExactlyAtTheNodes) {
  const auto I = fitted(5);
  for (size_t j = 0; j < I.numNodes(); ++j) EXPECT_EQ(I.evaluate(I.node(j)), f(I.node(j))) << "node " << j;
  // The box corners are nodes: a query at a bound hits them exactly.
  EXPECT_EQ(I.evaluate({1.1, 0.7}), f({1.1, 0.7}));
}

TEST(ParameterInterpolant, ReproducesPolynomialsOfDegreeBelowTheNodeCount) {
  // Degree 4 in each parameter with 5 nodes: exact up to the barycentric formula's round-off, a
  // few eps times the Lebesgue constant (about 2 for 5 Chebyshev points, per parameter).
  EXPECT_LT(worstRelative(fitted(5), 0), 1e-13);
  // With 4 nodes the degree-4 term cannot be represented: the check can fail.
  EXPECT_GT(worstRelative(fitted(4), 0), 1e-6);
}

TEST(ParameterInterpolant, ConvergesGeometricallyForAnAnalyticFunction) {
  const double e5 = worstRelative(fitted(5), 1), e7 = worstRelative(fitted(7), 1), e9 = worstRelative(fitted(9), 1);
  std::printf("exp(-8a) b: relative error %.2e / %.2e / %.2e with 5 / 7 / 9 nodes\n", e5, e7, e9);
  // Chebyshev interpolation of exp(8 h x), h = 0.3 the half-width: the coefficients fall like
  // I_j(2.4) ~ 1.2^j / j!, so two nodes more gain a factor of 30 to 50 (measured 27 and 35 in
  // the sup norm); a factor 10 fails an interpolant that is only algebraically convergent.
  EXPECT_LT(e7, e5 / 10);
  EXPECT_LT(e9, e7 / 10);
  EXPECT_LT(e9, 1e-4);
}

TEST(ParameterInterpolant, CheckPointsLieBetweenTheNodes) {
  // 3 Chebyshev-Lobatto nodes on [a, b] are a, (a + b) / 2, b: the midpoints of consecutive nodes
  // are (a + 3b) / 4 and (3a + b) / 4 in the nodes' order (x_i = cos(pi i / 2) mapped: b first), on
  // [1.1, 1.7] x [0.7, 1.3] the 2 x 2 grid below, the last parameter fastest; to the round-off of
  // the cosines (1e-15).
  const auto I = fitted(3);
  const auto pts = I.checkPoints(100);
  const std::vector<std::vector<double>> expected = {{1.55, 1.15}, {1.55, 0.85}, {1.25, 1.15}, {1.25, 0.85}};
  ASSERT_EQ(pts.size(), expected.size());
  for (size_t i = 0; i < pts.size(); ++i) {
    ASSERT_EQ(pts[i].size(), 2u);
    for (size_t p = 0; p < 2; ++p) EXPECT_NEAR(pts[i][p], expected[i][p], 1e-15) << "point " << i << ", parameter " << p;
    for (size_t j = 0; j < I.numNodes(); ++j) EXPECT_NE(pts[i], I.node(j));
  }
  // At most maxPoints, evenly strided through the same grid: 2 of 4 are the 1st and the 3rd.
  const auto two = I.checkPoints(2);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(two[0], pts[0]);
  EXPECT_EQ(two[1], pts[2]);
}

TEST(ParameterInterpolant, RefusesBadInput) {
  EXPECT_THROW(ParameterInterpolant({{0.0, 1.0}}, {1}, 1), gphr::InputError);
  EXPECT_THROW(ParameterInterpolant({{1.0, 1.0}}, {3}, 1), gphr::InputError);
  const auto I = fitted(3);
  EXPECT_THROW(I.evaluate({1.2}), gphr::InputError);
  EXPECT_THROW(I.evaluate({NAN, 1.0}), gphr::InputError);
}
