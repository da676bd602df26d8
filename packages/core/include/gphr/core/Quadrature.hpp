#pragma once
/// @file
/// Gauss-Legendre quadrature on [0, 1] for the averaged gradient of IMR / AVF.
#include <vector>

namespace gphr {

/// A quadrature rule on [0, 1]: nodes s_q and weights w_q (sum w_q = 1).
struct QuadratureRule {
  /// Nodes s_q in [0, 1] and weights w_q.
  /// @{
  std::vector<double> nodes, weights;
  /// @}
  int size() const { return static_cast<int>(nodes.size()); }  ///< Number of nodes.
};

/// Gauss-Legendre rule with `points` nodes on [0, 1] (Golub-Welsch: eigen-decomposition of the
/// Jacobi matrix with Teuchos::LAPACK STEQR). Exact for polynomials of degree 2 * points - 1.
QuadratureRule gaussLegendre(int points);

/// Fewest Gauss points that integrate grad H along a segment exactly when G has polynomial
/// degree `degree` (grad G and s * Hess G have degree degree - 1 in s): ceil(degree / 2), >= 1.
int gaussPointsForDegree(int degree);

}  // namespace gphr
