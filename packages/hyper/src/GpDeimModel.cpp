#include "gphr/hyper/GpDeimModel.hpp"

#include "gphr/reduction/SymmetricEigen.hpp"

namespace gphr {

GpDeimModel::GpDeimModel(RCP<const RowEvaluator> term, const SampleMesh& mesh)
    : ReducedHamiltonian(mesh.linear, rcp(new ReducedRowKernel(term, mesh.sample, Teuchos::null))),
      numbersHeld_(mesh.numbersHeld()) {}

RCP<GpDeimModel> buildGpDeimModel(const HamiltonianSystem& system, const MultiVector& A, const MultiVector& U, int m,
                                  const std::string& indexMethod, DeimWeights* diagnostics,
                                  const ReducedLinearPart* linear) {
  const auto idx = selectDeimIndices(U, m, indexMethod);
  const auto w = computeDeimWeights(U, idx, *system.nonlinearTerm().weights());
  if (diagnostics) *diagnostics = w;
  return rcp(new GpDeimModel(system.nonlinearTermPtr(),
                             buildSampleMesh(system, A, idx, w.weights, linear ? *linear : reduceLinearPart(system, A))));
}

double smallestEigenvalue(const DenseMatrix& H) {
  const int n = H.numRows();
  std::vector<double> a(static_cast<size_t>(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) a[i + static_cast<size_t>(n) * j] = 0.5 * (H(i, j) + H(j, i));
  return symmetricEigen(n, a.data(), false, "Hessian eigenvalues").front();
}

}  // namespace gphr
