#pragma once
/// @file
/// The symplectic Galerkin reduced model (paper eq:red_model): z' = J_{2k} grad H_r(z) with
/// H_r(z) = H(A z) = 1/2 z^T L_r z + z^T f_r + c + v^T G(A z). The nonlinear part is the full
/// system's row kernel on all d rows of G (each rank its own rows, basis rows imported once onto
/// the stencils, partial sums reduced): O(d s k^2) per Hessian, the cost the hyper-reduction removes.
/// z0 = A^T y0 (= 0 for the shifted system).
#include "gphr/reduction/ReducedHamiltonian.hpp"

namespace gphr {

/// The symplectic Galerkin reduced model H_r(z) = H(A z) (see the file's description).
class GalerkinRom final : public ReducedHamiltonian {
 public:
  /// The Galerkin ROM of `system` on the symplectic basis A (2n x 2k).
  GalerkinRom(RCP<const HamiltonianSystem> system, RCP<const MultiVector> A);

  /// y = A z (a state of the system), z = A^T y.
  void lift(const DenseVector& z, Vector& y) const;
  DenseVector project(const Vector& y) const;  ///< z = A^T y (collective).
  const DenseMatrix& reducedLinearPart() const { return linearPart().L; }  ///< L_r = A^T L A.
  const MultiVector& basis() const { return *A_; }  ///< The basis A.

 private:
  RCP<const HamiltonianSystem> sys_;
  RCP<const MultiVector> A_;
  RCP<const Map> localMap_;
  RCP<MultiVector> zLocal_;  ///< replicated buffer of lift(), allocated once
};

}  // namespace gphr
