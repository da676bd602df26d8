#pragma once
/// @file
/// The contract of a small Hamiltonian system z' = J_{2k} grad H(z), replicated on every rank: the
/// Galerkin reduced model and the hyper-reduced models implement it, the dense time scheme
/// (timeint's DenseBackend) integrates it.
#include "gphr/core/DenseTypes.hpp"
#include "gphr/core/Quadrature.hpp"

namespace gphr {

/// A small Hamiltonian system on R^{2k} with z = (z_q, z_p), replicated on every rank.
class DenseHamiltonian {
 public:
  virtual ~DenseHamiltonian() = default;
  virtual int dim() const = 0;  ///< 2k
  virtual double hamiltonian(const DenseVector& z) = 0;  ///< H(z).
  virtual void gradient(const DenseVector& z, DenseVector& g) = 0;  ///< g = grad H(z).
  /// H += scale * Hess H(z).
  virtual void addHessian(const DenseVector& z, double scale, DenseMatrix& H) = 0;
  /// The time scheme's averaged gradient gbar = sum_q w_q grad H((1 - s_q) z0 + s_q z1) at once,
  /// for a model that can do better than node by node (ReducedHamiltonian: its quadratic part and
  /// its stencil values are linear in z). Returns false (the default) to let the scheme loop.
  virtual bool averagedGradient(const DenseVector& z0, const DenseVector& z1, const QuadratureRule& rule,
                                DenseVector& gbar) {
    (void)z0, (void)z1, (void)rule, (void)gbar;
    return false;
  }
  /// H += scale * sum_q w_q s_q Hess H((1 - s_q) z0 + s_q z1), the scheme's Newton matrix term, at
  /// once, for a model that can do better than node by node (ReducedHamiltonian: one GEMM with the
  /// nodes' Hessian blocks summed instead of one per node). Returns false (the default) to let the
  /// scheme loop over the nodes with addHessian.
  virtual bool addAveragedHessian(const DenseVector& z0, const DenseVector& z1, const QuadratureRule& rule,
                                  double scale, DenseMatrix& H) {
    (void)z0, (void)z1, (void)rule, (void)scale, (void)H;
    return false;
  }
};

}  // namespace gphr
