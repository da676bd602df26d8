#pragma once
// The symplectic Galerkin reduced model (paper eq:red_model): z' = J_{2k} grad H_r(z) with
// H_r(z) = H(A z), so grad H_r = A^T grad H(A z) = L_r z + f_r + A^T J_G(Az)^T v and
// Hess H_r = L_r + A^T Hess N(A z) A, with L_r = A^T L A precomputed. The nonlinear part comes
// from the full system's row kernel on all d rows of A z (the cost the hyper-reduction removes).
// z0 = A^T y0 (= 0 for the shifted system).
#include "gphr/core/HamiltonianSystem.hpp"
#include "gphr/timeint/DenseBackend.hpp"

namespace gphr {

class GalerkinRom final : public DenseHamiltonian {
 public:
  GalerkinRom(RCP<const HamiltonianSystem> system, RCP<const MultiVector> A);

  int dim() const override { return static_cast<int>(A_->getNumVectors()); }
  double hamiltonian(const DenseVector& z) override;
  void gradient(const DenseVector& z, DenseVector& g) override;
  void addHessian(const DenseVector& z, double scale, DenseMatrix& H) override;

  // y = A z (a state of the system), z = A^T y.
  void lift(const DenseVector& z, Vector& y) const;
  DenseVector project(const Vector& y) const;
  const DenseMatrix& reducedLinearPart() const { return Lr_; }
  const MultiVector& basis() const { return *A_; }

 private:
  // out = A^T X (replicated, dim x X.cols); allocates, so only for set-up.
  DenseMatrix transposeTimes(const MultiVector& X) const;
  RCP<const HamiltonianSystem> sys_;
  RCP<const MultiVector> A_;
  DenseMatrix Lr_;
  RCP<Vector> y_, g_;
  RCP<CrsMatrix> hessN_;
  RCP<MultiVector> HA_;
  RCP<const Map> localMap_;
  // Replicated buffers of the time loop (allocated once): z, A^T y, A^T Hess N A.
  RCP<MultiVector> zLocal_, AtyLocal_, AtHALocal_;
};

}  // namespace gphr
