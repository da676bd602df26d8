#include "gphr/timeint/DenseBackend.hpp"

#include "gphr/core/Error.hpp"

namespace gphr {

DenseBackend::DenseBackend(DenseHamiltonian& model)
    : model_(model), hbar_(model.dim(), model.dim()), K_(model.dim(), model.dim()), pivots_(model.dim()) {}

void DenseBackend::endNewtonMatrix() {
  ++assemblies_;
  const int n = model_.dim(), k = n / 2;
  // K = I + J hbar: (J hbar)_{i,:} = hbar_{k+i,:}, (J hbar)_{k+i,:} = -hbar_{i,:}.
  for (int c = 0; c < n; ++c)
    for (int i = 0; i < k; ++i) {
      K_(i, c) = (i == c) + hbar_(k + i, c);
      K_(k + i, c) = (k + i == c) - hbar_(i, c);
    }
  int info = 0;
  lapack_.GETRF(n, n, K_.values(), K_.stride(), pivots_.data(), &info);
  GPHR_REQUIRE(info == 0, SolverError, "dense Newton matrix is singular (LAPACK GETRF info = ", info, ")");
}

int DenseBackend::solveNewton(const Vector& rhs, Vector& dx, double) {
  dx.assign(rhs);
  int info = 0;
  lapack_.GETRS('N', model_.dim(), 1, K_.values(), K_.stride(), pivots_.data(), dx.values(), dx.length(), &info);
  GPHR_REQUIRE(info == 0, SolverError, "dense Newton solve failed (LAPACK GETRS info = ", info, ")");
  return 0;
}

void DenseBackend::update(Vector& y, double a, const Vector& x, double b) {
  for (int i = 0; i < y.length(); ++i) y(i) = a * x(i) + b * y(i);
}

void DenseBackend::update(Vector& y, double a, const Vector& x, double b, const Vector& z, double c) {
  for (int i = 0; i < y.length(); ++i) y(i) = a * x(i) + b * z(i) + c * y(i);
}

}  // namespace gphr
