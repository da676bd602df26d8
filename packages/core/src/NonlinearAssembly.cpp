#include "gphr/core/NonlinearAssembly.hpp"

#include <Teuchos_CommHelpers.hpp>

#include "gphr/core/Error.hpp"

namespace gphr {

NonlinearAssembly::NonlinearAssembly(RCP<const NonlinearTerm> term) : term_(term) {
  const auto& graph = *term_->jacobianGraph();
  overlapMap_ = graph.getColMap();
  importer_ = term_->layout()->overlapImport;  // the layout's, shared by every system on it
  yOverlap_ = rcp(new Vector(overlapMap_));
  gradOverlap_ = rcp(new Vector(overlapMap_));
  yWork_ = rcp(new Vector(term_->stateMap()));
  gradOwned_ = rcp(new Vector(term_->stateMap()));
  const Stencil& st = term_->stencil();
  stencilLids_ = term_->layout()->stencilLids.data();
  std::vector<GO> rowIds(st.numRows());
  for (LO r = 0; r < st.numRows(); ++r) rowIds[r] = term_->rowMap()->getGlobalElement(r);
  batch_.allocate(rowIds, st.offsets, true, false);  // the Hessian's buffers when first asked for
  gRef_.assign(st.numRows(), 0.0);
}

void NonlinearAssembly::setReference(const RCP<const Vector>& yRef) {
  yRef_ = Teuchos::null;
  std::fill(gRef_.begin(), gRef_.end(), 0.0);
  if (yRef.is_null()) return;
  Vector zero(term_->stateMap());
  yRef_ = yRef;
  evaluate(zero, false, false);
  for (LO r = 0; r < batch_.size(); ++r) gRef_[r] = batch_.g(r);
}

void NonlinearAssembly::evaluate(const Vector& y, bool withGradient, bool withHessian) {
  if (yRef_.is_null()) {
    yOverlap_->doImport(y, *importer_, Tpetra::INSERT);
  } else {
    yWork_->update(1.0, y, 1.0, *yRef_, 0.0);
    yOverlap_->doImport(*yWork_, *importer_, Tpetra::INSERT);
  }
  {
    auto yv = yOverlap_->getLocalViewHost(Tpetra::Access::ReadOnly);
    auto vals = batch_.values;
    const LO* lids = stencilLids_;
    Kokkos::parallel_for(
        "gphr::gatherStencil", Kokkos::RangePolicy<ExecSpace>(0, vals.extent(0)),
        KOKKOS_LAMBDA(const size_t j) { vals(j) = yv(lids[j], 0); });
  }
  if (withHessian && !hessianAllocated_) {
    const size_t entries = batch_.hessOffsets(batch_.size());
    batch_.hess = HostView1("gphr::batch.hess", entries);
    hessVals_.resize(entries);
    hessianAllocated_ = true;
  }
  RowBatch b = batch_;
  if (!withGradient) b.grad = HostView1();
  if (!withHessian) b.hess = HostView1();
  term_->evaluate(b);
}

Scalar NonlinearAssembly::value() const {
  auto v = term_->weights()->getLocalViewHost(Tpetra::Access::ReadOnly);
  Scalar local = 0.0;
  for (LO r = 0; r < batch_.size(); ++r) local += v(r, 0) * (batch_.g(r) - gRef_[r]);
  Scalar global = 0.0;
  Teuchos::reduceAll(*term_->rowMap()->getComm(), Teuchos::REDUCE_SUM, local, Teuchos::outArg(global));
  return global;
}

void NonlinearAssembly::addGradient(Vector& out, Scalar scale, Scalar beta) const {
  gradOverlap_->putScalar(0.0);
  {
    auto v = term_->weights()->getLocalViewHost(Tpetra::Access::ReadOnly);
    auto gv = gradOverlap_->getLocalViewHost(Tpetra::Access::ReadWrite);
    const auto& off = term_->stencil().offsets;
    // Serial scatter: rows share stencil entries, so a parallel loop would need atomics.
    for (LO r = 0; r < batch_.size(); ++r)
      for (size_t j = off[r]; j < off[r + 1]; ++j) gv(stencilLids_[j], 0) += v(r, 0) * batch_.grad(j);
  }
  out.scale(beta);
  gradOwned_->putScalar(0.0);
  gradOwned_->doExport(*gradOverlap_, *importer_, Tpetra::ADD);
  out.update(scale, *gradOwned_, 1.0);
}

void NonlinearAssembly::fillJacobian(CrsMatrix& out) const {
  const Stencil& st = term_->stencil();
  out.resumeFill();
  out.setAllToScalar(0.0);
  for (LO r = 0; r < st.numRows(); ++r) {
    const LO s = st.size(r);
    out.sumIntoLocalValues(r, Teuchos::ArrayView<const LO>(&stencilLids_[st.offsets[r]], s),
                           Teuchos::ArrayView<const Scalar>(&batch_.grad(st.offsets[r]), s));
  }
  out.fillComplete(term_->stateMap(), term_->rowMap());
}

void NonlinearAssembly::addHessian(CrsMatrix& target, Scalar scale, const PhaseSpace* leftJ) const {
  GPHR_REQUIRE(hessianAllocated_, SolverError, "nonlinear assembly: addHessian before an evaluate() with the Hessian");
  const Stencil& st = term_->stencil();
  LocalScatter& scatter = hessScatter_[leftJ ? 1 : 0];
  const CrsGraph& graph = *target.getCrsGraph();
  if (!scatter.builtFor(&graph)) {  // once per target graph: entries in stencil-block order
    std::vector<GO> rows, cols;
    for (LO r = 0; r < st.numRows(); ++r) {
      const LO s = st.size(r);
      const GO* gids = &st.gids[st.offsets[r]];
      for (LO a = 0; a < s; ++a)
        for (LO c = 0; c < s; ++c) {
          rows.push_back(leftJ ? leftJ->jRow(gids[a]).first : gids[a]);
          cols.push_back(gids[c]);
        }
    }
    scatter = LocalScatter(graph, rows, cols);
  }
  auto v = term_->weights()->getLocalViewHost(Tpetra::Access::ReadOnly);
  size_t e = 0;
  for (LO r = 0; r < st.numRows(); ++r) {
    const LO s = st.size(r);
    const GO* gids = &st.gids[st.offsets[r]];
    const Scalar* h = &batch_.hess(batch_.hessOffsets(r));
    for (LO a = 0; a < s; ++a) {
      const Scalar sign = leftJ ? leftJ->jRow(gids[a]).second : 1.0;
      for (LO c = 0; c < s; ++c) hessVals_[e++] = sign * scale * v(r, 0) * h[a * s + c];
    }
  }
  scatter.add(target, hessVals_.data());
}

void NonlinearAssembly::insertHessianPattern(CrsGraph& graph, const PhaseSpace* leftJ) const {
  const Stencil& st = term_->stencil();
  for (LO r = 0; r < st.numRows(); ++r) {
    const LO s = st.size(r);
    const GO* gids = &st.gids[st.offsets[r]];
    for (LO a = 0; a < s; ++a)
      graph.insertGlobalIndices(leftJ ? leftJ->jRow(gids[a]).first : gids[a], Teuchos::ArrayView<const GO>(gids, s));
  }
}

}  // namespace gphr

namespace gphr {

std::vector<size_t> NonlinearAssembly::hessianRowBounds() const {
  Vector overlapCounts(overlapMap_), owned(term_->stateMap());
  {
    auto cv = overlapCounts.getLocalViewHost(Tpetra::Access::ReadWrite);
    const Stencil& st = term_->stencil();
    for (LO r = 0; r < st.numRows(); ++r)
      for (size_t j = st.offsets[r]; j < st.offsets[r + 1]; ++j) cv(stencilLids_[j], 0) += st.size(r);
  }
  owned.doExport(overlapCounts, *importer_, Tpetra::ADD);
  auto ov = owned.getLocalViewHost(Tpetra::Access::ReadOnly);
  std::vector<size_t> bounds(ov.extent(0));
  for (size_t i = 0; i < bounds.size(); ++i) bounds[i] = static_cast<size_t>(ov(i, 0) + 0.5);
  return bounds;
}

}  // namespace gphr
