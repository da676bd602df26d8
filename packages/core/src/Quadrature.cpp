#include "gphr/core/Quadrature.hpp"

#include <Teuchos_LAPACK.hpp>
#include <cmath>

#include "gphr/core/Error.hpp"

namespace gphr {

QuadratureRule gaussLegendre(int points) {
  GPHR_REQUIRE(points >= 1 && points <= 64, InputError, "Gauss-Legendre rule with ", points,
               " points is not allowed: use 1..64");
  // Jacobi matrix of the Legendre polynomials on [-1, 1]: zero diagonal, off-diagonal
  // k / sqrt(4k^2 - 1). Its eigenvalues are the nodes; weights are 2 * (first component)^2.
  std::vector<double> diag(points, 0.0), off(std::max(points - 1, 1), 0.0), z(points * points), work(std::max(1, 2 * points - 2));
  for (int k = 1; k < points; ++k) off[k - 1] = k / std::sqrt(4.0 * k * k - 1.0);
  int info = 0;
  Teuchos::LAPACK<int, double>().STEQR('I', points, diag.data(), off.data(), z.data(), points, work.data(), &info);
  GPHR_REQUIRE(info == 0, SolverError, "Gauss-Legendre: LAPACK STEQR failed with info = ", info);
  QuadratureRule r;
  for (int q = 0; q < points; ++q) {
    r.nodes.push_back(0.5 * (diag[q] + 1.0));    // map [-1, 1] -> [0, 1]
    r.weights.push_back(z[q * points] * z[q * points]);  // 2 v0^2 on [-1, 1], halved
  }
  return r;
}

int gaussPointsForDegree(int degree) { return degree <= 2 ? 1 : (degree + 1) / 2; }

}  // namespace gphr
