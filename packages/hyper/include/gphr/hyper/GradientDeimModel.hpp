#pragma once
/// @file
/// The baselines the paper compares GP-DEIM against (Sec.\ 5.2, fig:pcolor_n40_n60): DEIM applied
/// to the nonlinear *gradient* grad N (a 2n-vector), not to the reduced Jacobian:
///   F(z) = L_r z + f_r + A^T U_g (P_g^T U_g)^{-1} P_g^T grad N(y0 + A z)   (+ the pair's offset)
///   classic DEIM: U_g = POD of grad N snapshots;  SDEIM (PM16, AH17): U_g = the symplectic basis A
///   (without PM16's enrichment by extra snapshots), so m = 2k.
/// The classic DEIM's textbook form (Chaturantabut & Sorensen: snapshots of the nonlinear term at
/// the full model's states) with the shift of Sec. 3.3 interpolates grad N(y) - grad N(y0), exact
/// at the reference state as G_s(y0) = 0 makes GP-DEIM (eq:shiftH); the pair's offset adds
/// grad N(y0) back (see withReferenceGradient).
/// F is in general not a gradient field (its Jacobian is not symmetric): the model has no
/// Hamiltonian, and hamiltonian() returns NaN. Online it evaluates the rows of G whose stencils
/// hold a sampled entry (its own sample mesh).
#include "gphr/hyper/SampleMesh.hpp"
#include "gphr/core/SnapshotSet.hpp"
#include "gphr/core/SystemSet.hpp"

namespace gphr {

/// The DEIM pair of a gradient-DEIM baseline: sampled state entries P_g and the reduced operator B.
struct GradientDeimPair {
  std::vector<GO> entries;  ///< P_g: sampled entries of the state (global ids)
  DenseMatrix B;            ///< A^T U_g (P_g^T U_g)^{-1}: 2k x m
  DenseVector offset;       ///< added to F (2k), or empty: see withReferenceGradient
  double conditionNumber = 0.0;  ///< cond_2(P_g^T U_g)
};

/// Greedy DEIM on U_g (state map), m of its columns. Collective. F interpolates grad N itself.
GradientDeimPair makeGradientDeimPair(const MultiVector& Ug, int m, const MultiVector& A);

/// The pair interpolating grad N(y_s) - g0 instead, g0 = grad N at the system's state 0 (grad N(y0)
/// of a shifted system, eq:shiftH), g0 added back exactly: offset = A^T g0 - B P_g^T g0, so that
///   F(z) = L_r z + f_r + A^T g0 + A^T U_g (P_g^T U_g)^{-1} P_g^T (grad N(A z) - g0)
/// and F(0) is the Galerkin ROM's field at 0 for any m. For a basis of GradientSnapshots::Full.
/// Collective (one full gradient evaluation, offline).
GradientDeimPair withReferenceGradient(GradientDeimPair pair, const HamiltonianSystem& system, const MultiVector& A);

/// The grad N snapshots of the classic DEIM basis (hyper.deimSnapshots).
enum class GradientSnapshots {
  Full,       ///< grad N(y_s) - grad N(0) at the full model's training states y_s (the textbook DEIM
              ///< with the shift of Sec. 3.3: grad N(y) - grad N(y0) in physical variables)
  Projected,  ///< grad N(A A^T y_s) at the training states projected on the reduced basis, unshifted
};

/// POD (StreamingPod, maxRank columns) of the grad N snapshots of `kind` over every snapshotEvery-th
/// training state of each training system (shifted: state 0 is its y0).
RCP<MultiVector> gradientDeimBasis(const SystemSet& systems,
                                   const SnapshotSet& states, const MultiVector& A,
                                   int maxRank, int snapshotEvery, GradientSnapshots kind,
                                   std::vector<double>* singularValues = nullptr);

/// The classic DEIM / SDEIM baseline: the reduced field F(z) of the file's description (no Hamiltonian).
class GradientDeimModel final : public DenseHamiltonian {
 public:
  /// The baseline on `system` with basis A, pair `pair` and the reduced linear part.
  GradientDeimModel(const HamiltonianSystem& system, const MultiVector& A, const GradientDeimPair& pair,
                    ReducedLinearPart linear);
  int dim() const override { return linear_.L.numRows(); }
  double hamiltonian(const DenseVector& z) override;  ///< NaN: F is not a gradient field
  void gradient(const DenseVector& z, DenseVector& g) override;                 ///< g = F(z)
  void addHessian(const DenseVector& z, double scale, DenseMatrix& H) override;  ///< H += scale dF/dz
  /// Kernel rows evaluated per evaluation of F (rows whose stencils hold a sampled entry).
  LO kernelRowsPerEvaluation() const { return rows_->numRows(); }

 private:
  ReducedLinearPart linear_;
  DenseMatrix B_;
  DenseVector offset_;
  RCP<ReducedRowKernel> rows_;
  std::vector<int> entrySlot_;
  std::vector<Scalar> gP_, hP_;  ///< sampled gradient entries, their z-derivatives (m x 2k)
};

}  // namespace gphr
