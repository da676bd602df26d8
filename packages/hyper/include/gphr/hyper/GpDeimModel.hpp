#pragma once
/// @file
/// The gradient-preserving hyper-reduced model (paper eq:Hyperred_model):
///   H_hr(z) = 1/2 z^T L_r z + z^T f_r + c + sum_{i in P} w_i (G_i(y0 + A_Si z) - G_i(y0)),
///   grad H_hr = L_r z + f_r + A^T J_G(y0 + A z)^T P (U^T P)^{-1} U^T v,
/// a DenseHamiltonian on its sample mesh (replicated on every rank), so IMR/AVF and the dense
/// Newton serve it unchanged and it is Hamiltonian by construction.
#include "gphr/hyper/SampleMesh.hpp"
#include "gphr/reduction/Deim.hpp"

namespace gphr {

/// The GP-DEIM model: H_hr on its sample mesh, a DenseHamiltonian (see the file's description).
class GpDeimModel final : public ReducedHamiltonian {
 public:
  GpDeimModel(RCP<const RowEvaluator> term, const SampleMesh& mesh);  ///< The model of row kernel `term` on `mesh`.
  int deimSize() const { return rows().numRows(); }  ///< m, the DEIM size.
  /// Kernel rows evaluated per kernel evaluation (= m) and stencil entries held (= sum of s_i).
  LO kernelRowsPerEvaluation() const { return rows().numRows(); }
  /// Stencil entries held (= sum of s_i over the m rows).
  size_t stencilEntries() const { return rows().numStencilEntries(); }
  size_t numbersHeld() const { return numbersHeld_; }  ///< Numbers held online (doubles; independent of n and d).

 private:
  size_t numbersHeld_;
};

/// The whole online construction in one call, for users embedding GPHR: DEIM indices ("deim" or
/// "qdeim") from the first m columns of U, the weights from the system's v, the sample mesh and
/// the model. `diagnostics` (optional) receives the weights and cond(P^T U); `linear` (optional)
/// is L_r, f_r, c when the caller already has them (a sweep over m). Collective.
RCP<GpDeimModel> buildGpDeimModel(const HamiltonianSystem& system, const MultiVector& A, const MultiVector& U, int m,
                                  const std::string& indexMethod = "deim", DeimWeights* diagnostics = nullptr,
                                  const ReducedLinearPart* linear = nullptr);

/// Smallest eigenvalue of a symmetric Hessian (LAPACK SYEVD: a small dense eigenproblem, where an
/// Anasazi solve would cost more than it saves). Used to flag (k, m) whose H_hr is not convex
/// where H_r is (negative DEIM weights can do that).
double smallestEigenvalue(const DenseMatrix& H);

}  // namespace gphr
