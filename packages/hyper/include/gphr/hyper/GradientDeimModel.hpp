#pragma once
// The baselines the paper compares GP-DEIM against (Sec. 5.2, fig:pcolor_n40_n60): DEIM applied
// to the nonlinear *gradient* grad N (a 2n-vector), not to the reduced Jacobian:
//   F(z) = L_r z + f_r + A^T U_g (P_g^T U_g)^{-1} P_g^T grad N(y0 + A z)
//   classic DEIM: U_g = POD of grad N snapshots;  SDEIM (PM16, AH17): U_g = the symplectic basis A
//   (without PM16's enrichment by extra snapshots), so m = 2k.
// F is in general not a gradient field (its Jacobian is not symmetric): the model has no
// Hamiltonian, and hamiltonian() returns NaN. Online it evaluates the rows of G whose stencils
// hold a sampled entry (its own sample mesh).
#include "gphr/hyper/SampleMesh.hpp"

namespace gphr {

struct GradientDeimPair {
  std::vector<GO> entries;  // P_g: sampled entries of the state (global ids)
  DenseMatrix B;            // A^T U_g (P_g^T U_g)^{-1}: 2k x m
  double conditionNumber = 0.0;  // cond_2(P_g^T U_g)
};

// Greedy DEIM on U_g (state map), m of its columns. Collective.
GradientDeimPair makeGradientDeimPair(const MultiVector& Ug, int m, const MultiVector& A);

// POD (StreamingPod, maxRank columns) of grad N(y0_j + A A^T y_s) over the training states.
RCP<MultiVector> gradientDeimBasis(const std::vector<RCP<const HamiltonianSystem>>& systems,
                                   const std::vector<RCP<const MultiVector>>& states, const MultiVector& A,
                                   int maxRank, int snapshotEvery, std::vector<double>* singularValues = nullptr);

class GradientDeimModel final : public DenseHamiltonian {
 public:
  GradientDeimModel(const HamiltonianSystem& system, const MultiVector& A, const GradientDeimPair& pair,
                    ReducedLinearPart linear);
  int dim() const override { return linear_.L.numRows(); }
  double hamiltonian(const DenseVector& z) override;  // NaN: F is not a gradient field
  void gradient(const DenseVector& z, DenseVector& g) override;                 // g = F(z)
  void addHessian(const DenseVector& z, double scale, DenseMatrix& H) override;  // H += scale dF/dz
  LO kernelRowsPerEvaluation() const { return rows_->numRows(); }

 private:
  ReducedLinearPart linear_;
  DenseMatrix B_;
  RCP<ReducedRowKernel> rows_;
  std::vector<int> entrySlot_;
  std::vector<Scalar> gP_, hP_;  // sampled gradient entries, their z-derivatives (m x 2k)
};

}  // namespace gphr
