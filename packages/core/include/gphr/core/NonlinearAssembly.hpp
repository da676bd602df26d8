#pragma once
/// @file
/// Assembles, from the row kernel of a NonlinearTerm evaluated on all of this rank's rows of G,
/// the distributed quantities of the full model: N(y) = v^T G, grad N = J_G^T v, J_G and the
/// Hessian of N = sum_i v_i Hess G_i. No scene writes these assemblies itself.
///
/// The evaluation point is y + yRef (yRef = 0 unless the system is shifted, paper eq:shiftH),
/// and N subtracts v^T G(yRef). Buffers are allocated once, never in a time loop: the Hessian's
/// (s^2 numbers per row, twice) at the first evaluation that asks for it, since most systems are
/// never asked (a model file's interpolation nodes instantiate 57 SWE systems for their projections
/// alone; at SWE 256^2 on one rank they were 26 MB per system, zero-filled).
#include "gphr/core/LocalScatter.hpp"
#include "gphr/core/NonlinearTerm.hpp"
#include "gphr/core/PhaseSpace.hpp"

namespace gphr {

/// The full model's assembly of N, grad N, J_G and Hess N from a NonlinearTerm's row kernel on all rows of G.
class NonlinearAssembly {
 public:
  explicit NonlinearAssembly(RCP<const NonlinearTerm> term);  ///< Assembly for the row kernel and layout of `term`.

  const NonlinearTerm& term() const { return *term_; }  ///< The nonlinearity assembled.
  /// Set the reference point of the shift: later evaluations use y + yRef and N subtracts
  /// v^T G(yRef). Pass nullptr for no shift.
  void setReference(const RCP<const Vector>& yRef);
  /// The reference point of the shift (null if unshifted).
  const RCP<const Vector>& reference() const { return yRef_; }

  /// Evaluate the kernel at y (+ yRef); derivatives only as asked.
  void evaluate(const Vector& y, bool withGradient, bool withHessian);

  /// After evaluate(): N = sum_i v_i (G_i - G_i(yRef)) (a collective reduction).
  Scalar value() const;
  /// After evaluate(..., true, ...): out = scale * J_G^T v + beta * out  (grad N when scale = 1).
  void addGradient(Vector& out, Scalar scale, Scalar beta) const;
  /// After evaluate(..., true, ...): out = J_G, filled on jacobianGraph().
  void fillJacobian(CrsMatrix& out) const;
  /// After evaluate(..., ..., true): target += scale * Hess N, or scale * J Hess N when leftJ is
  /// given (row r of Hess N goes to row partner(r) with the sign of J). target must be fill-active
  /// and its graph hold those entries; off-rank rows are summed in at fillComplete.
  void addHessian(CrsMatrix& target, Scalar scale, const PhaseSpace* leftJ = nullptr) const;
  /// Sparsity of Hess N (or J Hess N) on the state map: all pairs of one stencil.
  void insertHessianPattern(CrsGraph& graph, const PhaseSpace* leftJ = nullptr) const;
  /// Upper bound of the Hessian entries of each owned state row (graphs are static-profile):
  /// sum of the sizes of the stencils that contain the row, summed over ranks.
  std::vector<size_t> hessianRowBounds() const;

  /// Values of G at the local rows after evaluate() (G(y + yRef), not shifted).
  const HostView1& rowValues() const { return batch_.g; }

 private:
  RCP<const NonlinearTerm> term_;
  RCP<const Map> overlapMap_;  ///< = column map of J_G: owned + ghost state entries
  RCP<const Import> importer_;  ///< the term layout's
  RCP<Vector> yOverlap_, gradOverlap_, yWork_, gradOwned_;
  RCP<const Vector> yRef_;
  /// stencil entries as local ids of overlapMap_ (the term layout's array; term_ keeps it alive)
  const LO* stencilLids_ = nullptr;
  RowBatch batch_;
  std::vector<Scalar> gRef_;  ///< G_i(yRef)
  mutable LocalScatter hessScatter_[2];  ///< per target graph, without / with J applied
  mutable std::vector<Scalar> hessVals_;
  bool hessianAllocated_ = false;  ///< batch_.hess and hessVals_ sized (at the first evaluate with the Hessian)
};

}  // namespace gphr
