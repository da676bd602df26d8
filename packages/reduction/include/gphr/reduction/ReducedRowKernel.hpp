#pragma once
/// @file
/// The row kernel of G evaluated in reduced coordinates on a set of rows (paper eq:redgrad,
/// eq:hhr_and_gradhhr, DESIGN.md "The sample mesh"): at y = yref + A z, with A_Si the rows of the
/// basis A under the stencil of row i,
///   value    sum_i w_i (G_i(y) - G_i(yref))
///   gradient sum_i w_i A_Si^T grad G_i(y)                     (2k)
///   Hessian  sum_i w_i A_Si^T Hess G_i(y) A_Si                (2k x 2k)
///   Jacobian rows  grad G_i(y)^T A_Si = row i of J_G(y) A      (eq:snaps_JG)
/// The Galerkin ROM runs it on each rank's own rows of G with w = v (partial sums reduced over
/// the ranks); the hyper-reduced models on the m sampled rows, replicated, with the DEIM weights.
/// One kernel evaluation gives value, gradient and Hessian together.
///
/// Kernels: Kokkos parallel_for over stencil entries (values y = yref + A_S z) and over rows
/// (the blocks w_i Hess G_i A_Si), and KokkosBlas GEMV / GEMM with the stacked basis rows (an
/// M x 2k matrix, M = sum of the stencil sizes; BLAS on a host build, device kernels on a GPU
/// build). Buffers are allocated once, at construction.
#include <Teuchos_SerialDenseMatrix.hpp>
#include <Teuchos_SerialDenseVector.hpp>
#include <vector>

#include "gphr/core/HamiltonianSystem.hpp"

namespace gphr {

/// A set of rows of G in reduced coordinates: everything an evaluation needs, nothing of size n or d.
struct RowSample {
  std::vector<GO> rows;            ///< global ids of the rows of G
  Stencil stencil;                 ///< their stencils (gids in the kernel's order)
  std::vector<Scalar> weights;     ///< w_i, one per row
  std::vector<Scalar> basisRows;   ///< per stencil entry, the 2k entries of that row of A (M x 2k, row-major)
  std::vector<Scalar> reference;   ///< per stencil entry, yref (zeros when the system is not shifted)
  bool shifted = false;            ///< subtract G_i(yref) in value() (paper eq:shiftH)
  int reducedDim = 0;              ///< 2k
};

/// The row kernel of G in reduced coordinates on a row sample (see the file's description).
class ReducedRowKernel {
 public:
  using DenseVector = Teuchos::SerialDenseVector<int, double>;  ///< Small dense vector (Teuchos).
  using DenseMatrix = Teuchos::SerialDenseMatrix<int, double>;  ///< Small dense matrix (Teuchos, column-major).

  /// sumOver: the communicator whose ranks hold disjoint parts of one row set (partial sums are
  /// reduced over it), or null when every rank holds the whole (replicated) sample.
  ReducedRowKernel(RCP<const RowEvaluator> term, RowSample sample, RCP<const Comm> sumOver);

  int reducedDim() const { return sample_.reducedDim; }  ///< 2k, the reduced size.
  LO numRows() const { return static_cast<LO>(sample_.rows.size()); }  ///< Number of rows of G in the sample.
  /// Number of stencil entries M (the sum of the stencil sizes).
  size_t numStencilEntries() const { return sample_.stencil.gids.size(); }
  const RowSample& sample() const { return sample_; }  ///< The row sample.
  void setWeights(const std::vector<Scalar>& w);  ///< Replaces the weights w_i (one per row).

  /// Run the kernel once at y = yref + A_S z; derivatives as asked.
  void evaluate(const DenseVector& z, bool withGradient, bool withHessian);
  /// After evaluate(): the sums above (collective when sumOver is set).
  double value() const;
  void addGradient(DenseVector& g, double scale) const;          ///< g += scale * gradient
  /// g += scale * sum_q w_q gradient((1 - s_q) z0 + s_q z1): the time scheme's averaged gradient
  /// (nodes s_q, weights w_q). The stencil values at every node are combinations of A_S z0 (kept
  /// while z0 is unchanged: the Newton iterations of a step) and A_S z1, and the kernel's weighted
  /// gradients are summed over the nodes before one A_S^T product: per Newton iteration the basis
  /// rows are read twice instead of twice per node. Leaves the kernel evaluated at the last node.
  void addAveragedGradient(const DenseVector& z0, const DenseVector& z1, const std::vector<double>& nodes,
                           const std::vector<double>& weights, DenseVector& g, double scale);
  void addHessian(DenseMatrix& H, double scale) const;           ///< H += scale * Hessian
  /// H += scale * sum_q c_q Hessian((1 - s_q) z0 + s_q z1): the time scheme's Newton matrix term
  /// (nodes s_q, coefficients c_q = w_q s_q). The Hessian is sum_i A_Si^T D_i A_Si with the same
  /// basis rows at every node, so the nodes' weighted blocks c_q w_i Hess G_i are summed first and
  /// the O(M (2k)^2) product A_S^T W is formed once instead of once per node. Leaves the kernel
  /// evaluated at the last node.
  void addAveragedHessian(const DenseVector& z0, const DenseVector& z1, const std::vector<double>& nodes,
                          const std::vector<double>& coefficients, DenseMatrix& H, double scale);
  /// After evaluate(z, true, ...): rows of J_G(y) A of this sample, row-major numRows() x 2k, row i
  /// at out + i * ld (ld = 0: 2k; a larger ld writes into columns of a wider array).
  void reducedJacobian(Scalar* out, size_t ld = 0) const;
  /// After evaluate(): each row's own G_i(y) - G_i(yref), unweighted (out: numRows() numbers).
  void rowValues(Scalar* out) const;
  /// Entries of grad N = sum_i w_i grad G_i at state entries (classic DEIM of the gradient):
  /// entrySlot[j] = slot of stencil entry j (-1: not sampled). out[slot] = sum of w_i dG_i/dy_e;
  /// entryHessianRows: out (numSlots x 2k, row-major) = the rows d(grad N)_e/dz.
  void entryGradients(const std::vector<int>& entrySlot, int numSlots, Scalar* out) const;
  void entryHessianRows(const std::vector<int>& entrySlot, int numSlots, Scalar* out) const;  ///< See entryGradients().

 private:
  using Rows2 = Kokkos::View<Scalar**, Kokkos::LayoutRight, Kokkos::HostSpace>;
  /// A_S^T as a column-major r x M view of AS_'s memory (KokkosBlas' instantiated layout).
  using ConstColMajor = Kokkos::View<const Scalar**, Kokkos::LayoutLeft, Kokkos::HostSpace, Kokkos::MemoryUnmanaged>;
  ConstColMajor basisT() const { return ConstColMajor(AS_.data(), static_cast<size_t>(reducedDim()), AS_.extent(0)); }
  void weightedGradients() const;      ///< u = w_i grad G_i per stencil entry
  void stencilValues(const DenseVector& z, HostView1 out) const;  ///< out = A_S z
  void reduceToGradient(const HostView1& u, DenseVector& g, double scale) const;  ///< g += scale A_S^T u (summed)
  void weightedHessianBlocks(const HostView1& hess) const;  ///< W = w_i hess_i A_Si per row
  void addBlockProduct(DenseMatrix& H, double scale) const;  ///< H += scale A_S^T W (summed over sumOver)
  void setZ0(const DenseVector& z0);                         ///< v0_ = A_S z0 unless z0 is the cached one
  /// values = yref + (1 - s) v0_ + s v1_ (the quadrature node s on [z0, z1]), then b evaluated.
  void evaluateAtNode(double s, const RowBatch& b);
  RCP<const RowEvaluator> term_;
  RowSample sample_;
  RCP<const Comm> sumOver_;
  RowBatch batch_;
  Rows2 AS_, W_;                       ///< stacked basis rows; w_i Hess G_i A_Si
  HostView1 yref_, u_, w_, gRef_;       ///< per entry: yref, w_i grad; per row: w_i, G_i(yref)
  HostView1 v0_, v1_, uSum_;            ///< per entry: A_S z0, A_S z1, sum_q w_q w_i grad (averaged gradient)
  HostView1 hessSum_;                   ///< per row: sum_q c_q Hess G_i (averaged Hessian)
  DenseVector z0_;                      ///< the z0 of v0_
  bool haveZ0_ = false;
  IndexView entryRow_;                 ///< row of each stencil entry
  mutable std::vector<Scalar> gradBuf_, hessBuf_, sumBuf_;
};

/// This rank's own rows of G with w = v, basis rows imported onto the stencils' overlap:
/// the Galerkin ROM's sample (reduce it over the state map's communicator). Collective.
RowSample ownedRowSample(const HamiltonianSystem& system, const MultiVector& A);

}  // namespace gphr
