#pragma once
/// @file
/// The decomposed nonlinearity N(y) = v^T G(y) of paper eq:decomp, G : R^{2n} -> R^d, given
/// row by row: row i of G depends only on the entries of y in its *stencil* (s1 + s2 of them,
/// paper rmk:decomp). A scene supplies a row kernel; everything else (N, grad N = J_G^T v, J_G,
/// the Hessian of N, and later the sampled rows of the hyper-reduced model) is assembled by GPHR
/// from that one kernel.
///
/// Row-kernel contract (a copyable functor, see RowKernelTerm below):
///   KOKKOS_INLINE_FUNCTION
///   void operator()(GO row, const Scalar* vals, Scalar& g, Scalar* grad, Scalar* hess) const;
///     vals: y at the row's stencil (stencil order), g: G_row(y);
///     grad (may be nullptr): dG_row/dvals (s entries);
///     hess (may be nullptr): d^2 G_row/dvals^2, s x s row-major.
/// The stencils themselves (which entries, hence s) are data, given once as a Stencil of the
/// owned rows; gatherStencils (ReplicatedGather.hpp) collects those of any set of global rows.
/// The kernel may be called on any row id with any values: the full model calls it on owned
/// rows, the reduced and hyper-reduced models on rows they hold replicated.
#include <memory>
#include <string>
#include <vector>

#include "gphr/core/Types.hpp"

namespace gphr {

/// Global stencil of this rank's rows of G: row r's entries are gids[offsets[r]..offsets[r+1]),
/// listed in the kernel's order.
struct Stencil {
  std::vector<size_t> offsets{0};  ///< Row r's entries are gids[offsets[r] .. offsets[r+1]).
  std::vector<GO> gids;  ///< Global ids (entries of y) of all stencils, row after row.
  LO numRows() const { return static_cast<LO>(offsets.size()) - 1; }  ///< Number of rows.
  LO size(LO r) const { return static_cast<LO>(offsets[r + 1] - offsets[r]); }  ///< Stencil size s of row r.
};

/// A batch of rows to evaluate: for entry e, row id rows(e), stencil values
/// values(offsets(e)..offsets(e+1)). Outputs are filled where their view is non-empty:
/// g(e); grad packed like values; hess at hessOffsets(e) .. + s*s.
struct RowBatch {
  Kokkos::View<GO*, Kokkos::HostSpace> rows;  ///< Row id (of G) of each entry.
  /// Offsets of each entry's stencil values and gradient / of its s x s Hessian.
  /// @{
  OffsetView offsets, hessOffsets;
  /// @}
  /// Stencil values (input); G_row, its gradient and Hessian (outputs, where non-empty).
  /// @{
  HostView1 values, g, grad, hess;
  /// @}
  LO size() const { return static_cast<LO>(rows.extent(0)); }  ///< Number of entries.
  /// Allocate for the given stencil layout (done once, outside any time loop).
  void allocate(const std::vector<GO>& rowIds, const std::vector<size_t>& stencilOffsets,
                bool withGradient, bool withHessian);
};

/// The row kernel alone, at one parameter value: what the reduced and hyper-reduced models call.
/// It holds no maps, stencils or weights (nothing of size n or d), so an online model loaded from
/// a reduced-model file runs it without the full system.
class RowEvaluator {
 public:
  virtual ~RowEvaluator() = default;
  /// Run the row kernel on every entry of the batch (Kokkos::parallel_for over the entries).
  virtual void evaluate(const RowBatch& batch) const = 0;
  /// Polynomial degree of G in y (0 if not polynomial): AVF picks its quadrature from it.
  int polynomialDegree() const { return degree_; }
  /// Entries of y every row's stencil has (the kernel reads that many values), or 0 where rows
  /// differ: a sample mesh read from a file is checked against it before the kernel runs.
  int stencilSize() const { return stencilSize_; }

 protected:
  /// Evaluator of a row kernel whose G is a polynomial of degree `degree` (0: not polynomial) and
  /// whose rows each read `stencilSize` entries (0: not the same for every row).
  explicit RowEvaluator(int degree, int stencilSize = 0) : degree_(degree), stencilSize_(stencilSize) {}

 private:
  int degree_, stencilSize_;
};

/// The one place a row kernel is called: a parallel_for over the rows of a batch. The virtual
/// call is per batch, never per row.
template <class Kernel>
void runRowKernel(const Kernel& kernel, const RowBatch& b) {
  const Kernel k = kernel;
  const auto rows = b.rows;
  const auto off = b.offsets;
  const auto hoff = b.hessOffsets;
  const auto vals = b.values;
  const auto g = b.g;
  const auto grad = b.grad;
  const auto hess = b.hess;
  const bool wantG = g.extent(0) > 0, wantGrad = grad.extent(0) > 0, wantHess = hess.extent(0) > 0;
  Kokkos::parallel_for(
      "gphr::rowKernel", Kokkos::RangePolicy<ExecSpace>(0, b.size()), KOKKOS_LAMBDA(const LO e) {
        Scalar ge = 0.0;
        k(rows(e), &vals(off(e)), ge, wantGrad ? &grad(off(e)) : nullptr, wantHess ? &hess(hoff(e)) : nullptr);
        if (wantG) g(e) = ge;
      });
}

/// A RowEvaluator over a kernel functor (see the contract above).
template <class Kernel>
class KernelRows final : public RowEvaluator {
 public:
  /// Wraps `kernel`; `degree` as in polynomialDegree().
  KernelRows(const Kernel& kernel, int degree, int stencilSize = 0)
      : RowEvaluator(degree, stencilSize), kernel_(kernel) {}
  void evaluate(const RowBatch& b) const override { runRowKernel(kernel_, b); }

 private:
  Kernel kernel_;
};

/// A RowEvaluator over a kernel functor (KernelRows): G of polynomial degree `degree`, each row
/// reading `stencilSize` entries of y (0: not the same for every row).
template <class Kernel>
RCP<const RowEvaluator> makeRowEvaluator(const Kernel& kernel, int degree, int stencilSize = 0) {
  return rcp(new KernelRows<Kernel>(kernel, degree, stencilSize));
}

/// The layout of a decomposed nonlinearity, everything of it but the row kernel: the maps, this
/// rank's stencils, the weights v, the sparsity of J_G and the import of the stencils' state
/// entries. It does not depend on the scene's parameters, so systems built at many parameter values
/// on one communicator (a model file's interpolation nodes) share one (Scene::rebuild).
struct TermLayout {
  /// The layout of rows on `rowMap` with stencils `stencil` into states on `stateMap`, weights v.
  TermLayout(RCP<const Map> rowMap, RCP<const Map> stateMap, Stencil stencil, RCP<const Vector> weights);
  RCP<const Map> rowMap;  ///< Distribution of the d rows of G.
  RCP<const Map> stateMap;  ///< The state map (2n entries).
  Stencil stencil;  ///< Stencils of this rank's rows of G.
  RCP<const Vector> weights;  ///< The weights v of N = v^T G, on rowMap.
  int maxStencil = 0;  ///< Largest stencil size s over this rank's rows.
  RCP<const CrsGraph> jacobianGraph;  ///< Sparsity of J_G: row map rowMap, domain stateMap, range rowMap.
  RCP<const Import> overlapImport;  ///< stateMap -> the column map of J_G (owned and ghost state entries).
  std::vector<LO> stencilLids;  ///< The stencils' entries as local ids of J_G's column map.
};

/// The decomposed nonlinearity of a full system: the row kernel with the layout of the rows of G
/// (maps, stencils, weights v, the sparsity of J_G).
class NonlinearTerm : public RowEvaluator {
 public:
  /// d, the number of terms (rows of G).
  GO numTerms() const { return static_cast<GO>(layout_->rowMap->getGlobalNumElements()); }
  const RCP<const Map>& rowMap() const { return layout_->rowMap; }  ///< Distribution of the d rows of G.
  const RCP<const Map>& stateMap() const { return layout_->stateMap; }  ///< The state map (2n entries).
  const RCP<const Vector>& weights() const { return layout_->weights; }  ///< The weights v of N = v^T G, on rowMap().
  const Stencil& stencil() const { return layout_->stencil; }  ///< Stencils of this rank's rows of G.
  int maxStencilSize() const { return layout_->maxStencil; }  ///< Largest stencil size s over all rows.
  /// Sparsity of J_G (d rows x 2n columns): row map rowMap(), domain stateMap(), range rowMap().
  const RCP<const CrsGraph>& jacobianGraph() const { return layout_->jacobianGraph; }
  /// The layout alone, to share with a term of another kernel (Scene::rebuild).
  const std::shared_ptr<const TermLayout>& layout() const { return layout_; }

 protected:
  /// A nonlinearity with rows on `rowMap`, states on `stateMap`, this rank's stencils and weights v.
  NonlinearTerm(RCP<const Map> rowMap, RCP<const Map> stateMap, Stencil stencil,
                RCP<const Vector> weights, int degree);
  /// A nonlinearity on an existing layout.
  NonlinearTerm(std::shared_ptr<const TermLayout> layout, int degree);

 private:
  std::shared_ptr<const TermLayout> layout_;
};

/// A NonlinearTerm over a row-kernel functor (the file's row-kernel contract): what a scene supplies.
template <class Kernel>
class RowKernelTerm final : public NonlinearTerm {
 public:
  /// The row kernel `kernel` with its layout (maps, stencils, weights v) and polynomial degree.
  RowKernelTerm(const Kernel& kernel, RCP<const Map> rowMap, RCP<const Map> stateMap,
                Stencil stencil, RCP<const Vector> weights, int degree)
      : NonlinearTerm(rowMap, stateMap, std::move(stencil), weights, degree), kernel_(kernel) {}
  /// The row kernel `kernel` on an existing layout (another term's, NonlinearTerm::layout()).
  RowKernelTerm(const Kernel& kernel, std::shared_ptr<const TermLayout> layout, int degree)
      : NonlinearTerm(std::move(layout), degree), kernel_(kernel) {}

  const Kernel& kernel() const { return kernel_; }  ///< The row-kernel functor.
  void evaluate(const RowBatch& b) const override { runRowKernel(kernel_, b); }

 private:
  Kernel kernel_;
};

/// A NonlinearTerm over a row-kernel functor (RowKernelTerm).
template <class Kernel>
RCP<const NonlinearTerm> makeRowKernelTerm(const Kernel& kernel, RCP<const Map> rowMap,
                                           RCP<const Map> stateMap, Stencil stencil,
                                           RCP<const Vector> weights, int degree) {
  return rcp(new RowKernelTerm<Kernel>(kernel, rowMap, stateMap, std::move(stencil), weights, degree));
}

/// A NonlinearTerm over a row-kernel functor on the layout of `like` (its maps, stencils, weights
/// and J_G's graph): no graph is built.
template <class Kernel>
RCP<const NonlinearTerm> makeRowKernelTerm(const Kernel& kernel, const NonlinearTerm& like, int degree) {
  return rcp(new RowKernelTerm<Kernel>(kernel, like.layout(), degree));
}

}  // namespace gphr
