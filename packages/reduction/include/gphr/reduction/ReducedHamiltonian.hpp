#pragma once
/// @file
/// A Hamiltonian in reduced coordinates z in R^{2k}:
///   H(z) = 1/2 z^T L_r z + z^T f_r + c + sum_i w_i (G_i(yref + A_Si z) - G_i(yref))
/// The Galerkin ROM (eq:red_model; all rows of G, w = v) and the hyper-reduced models
/// (eq:Hyperred_model; m sampled rows, w = DEIM weights) are this class with different row
/// samples: the time schemes, Newton and the report see one DenseHamiltonian.
#include "gphr/reduction/ReducedRowKernel.hpp"
#include "gphr/core/DenseHamiltonian.hpp"

namespace gphr {

/// L_r = A^T L A, f_r = A^T f and the constant c of a (possibly shifted) system: computed once,
/// shared by the reduced and hyper-reduced models (with the shift, f_r = A^T (f + L y0) != 0).
struct ReducedLinearPart {
  DenseMatrix L;  ///< L_r = A^T L A (2k x 2k).
  DenseVector f;  ///< f_r = A^T f (2k).
  double c = 0.0;  ///< The constant c of H.
};
/// L_r, f_r and c of `system` on the basis A. Collective.
ReducedLinearPart reduceLinearPart(const HamiltonianSystem& system, const MultiVector& A);

/// A Hamiltonian in reduced coordinates on a row sample: the Galerkin ROM and the hyper-reduced models.
class ReducedHamiltonian : public DenseHamiltonian {
 public:
  /// H = 1/2 z^T L_r z + z^T f_r + c + the rows' sum, on the row sample `rows`.
  ReducedHamiltonian(ReducedLinearPart linear, RCP<ReducedRowKernel> rows);

  int dim() const override { return linear_.L.numRows(); }
  double hamiltonian(const DenseVector& z) override;
  void gradient(const DenseVector& z, DenseVector& g) override;
  void addHessian(const DenseVector& z, double scale, DenseMatrix& H) override;
  /// L_r zbar + (sum w_q) f_r with zbar = sum_q w_q z_q (the quadratic part is exact at the
  /// average point: one L_r product per Newton iteration), plus the rows' averaged gradient.
  bool averagedGradient(const DenseVector& z0, const DenseVector& z1, const QuadratureRule& rule,
                        DenseVector& gbar) override;
  /// H += scale sum_q c_q Hess H(z_q), c_q = w_q s_q: (scale sum_q c_q) L_r once, plus the rows'
  /// averaged Hessian (one A_S^T W product for all nodes).
  bool addAveragedHessian(const DenseVector& z0, const DenseVector& z1, const QuadratureRule& rule, double scale,
                          DenseMatrix& H) override;

  const ReducedLinearPart& linearPart() const { return linear_; }  ///< L_r, f_r, c.
  const ReducedRowKernel& rows() const { return *rows_; }  ///< The row sample and its kernel.
  ReducedRowKernel& rows() { return *rows_; }  ///< The row sample and its kernel.
  /// Kernel evaluations so far (one per distinct point: value, gradient and Hessian at the same z
  /// share one evaluation).
  long kernelEvaluations() const { return evaluations_; }

 protected:
  /// A model whose row sample moves (GP-ADEIM) swaps it here; the cached evaluation is dropped.
  void replaceRows(RCP<ReducedRowKernel> rows);
  /// The row kernel was evaluated elsewhere (at another z): the cached evaluation is stale.
  void forgetEvaluation() { haveLast_ = false; }

 private:
  void evaluateAt(const DenseVector& z);
  ReducedLinearPart linear_;
  RCP<ReducedRowKernel> rows_;
  DenseVector lastZ_, zbar_, lz_;
  bool haveLast_ = false;
  long evaluations_ = 0;
};

}  // namespace gphr
