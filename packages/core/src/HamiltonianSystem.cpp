#include "gphr/core/HamiltonianSystem.hpp"

#include "gphr/core/Error.hpp"

namespace gphr {

HamiltonianSystem::HamiltonianSystem(RCP<const PhaseSpace> space, RCP<const CrsMatrix> L,
                                     RCP<const Vector> f, Scalar c, RCP<const NonlinearTerm> nonlinear)
    : space_(space), L_(L), f_(f), c_(c), term_(nonlinear), assembly_(nonlinear) {
  GPHR_REQUIRE(L_->isFillComplete() && L_->getRowMap()->isSameAs(*space_->map()), InputError,
               "Hamiltonian: L must be a fill-complete matrix whose row map is the state map");
  GPHR_REQUIRE(f_->getMap()->isSameAs(*space_->map()), InputError,
               "Hamiltonian: f must live on the state map");
  GPHR_REQUIRE(term_->stateMap()->isSameAs(*space_->map()), InputError,
               "Hamiltonian: the nonlinear term's stencils must refer to the state map");
  work_ = rcp(new Vector(space_->map()));
}

RCP<HamiltonianSystem> HamiltonianSystem::shifted(const Vector& y0) const {
  auto fs = rcp(new Vector(*f_, Teuchos::Copy));
  L_->apply(y0, *fs, Teuchos::NO_TRANS, 1.0, 1.0);  // f_s = f + L y0
  auto ref = rcp(new Vector(y0, Teuchos::Copy));
  if (!reference().is_null()) ref->update(1.0, *reference(), 1.0);
  auto s = rcp(new HamiltonianSystem(space_, L_, fs, hamiltonian(y0), term_));
  s->assembly_.setReference(ref);
  return s;
}

Scalar HamiltonianSystem::nonlinearValue(const Vector& y) const {
  assembly_.evaluate(y, false, false);
  return assembly_.value();
}

Scalar HamiltonianSystem::hamiltonian(const Vector& y) const {
  L_->apply(y, *work_);
  return 0.5 * y.dot(*work_) + y.dot(*f_) + c_ + nonlinearValue(y);
}

void HamiltonianSystem::nonlinearRows(const Vector& y, Vector& out) const {
  assembly_.evaluate(y, false, false);
  auto ov = out.getLocalViewHost(Tpetra::Access::OverwriteAll);
  const auto& g = assembly_.rowValues();
  for (size_t r = 0; r < g.extent(0); ++r) ov(r, 0) = g(r);
}

void HamiltonianSystem::nonlinearGradient(const Vector& y, Vector& out) const {
  assembly_.evaluate(y, true, false);
  assembly_.addGradient(out, 1.0, 0.0);
}

void HamiltonianSystem::gradient(const Vector& y, Vector& out) const {
  assembly_.evaluate(y, true, false);
  L_->apply(y, out);
  out.update(1.0, *f_, 1.0);
  assembly_.addGradient(out, 1.0, 1.0);
}

RCP<CrsMatrix> HamiltonianSystem::createJacobianG() const {
  return rcp(new CrsMatrix(term_->jacobianGraph()));
}

void HamiltonianSystem::jacobianG(const Vector& y, CrsMatrix& out) const {
  assembly_.evaluate(y, true, false);
  assembly_.fillJacobian(out);
}

RCP<const CrsGraph> HamiltonianSystem::hessianGraph(bool leftJ) const {
  auto& cached = hessGraph_[leftJ ? 1 : 0];
  if (!cached.is_null()) return cached;
  const auto& map = space_->map();
  const PhaseSpace* J = leftJ ? space_.get() : nullptr;
  // Static profile: capacity = stencil bound + entries of L + diagonal, taken from the source row
  // (row r of H lands in row jRow(r) of J H, on the same rank: q_i and p_i are co-located).
  const std::vector<size_t> hb = assembly_.hessianRowBounds();
  std::vector<size_t> bounds(hb.size());
  for (LO i = 0; i < static_cast<LO>(hb.size()); ++i) {
    const LO target = leftJ ? map->getLocalElement(J->jRow(map->getGlobalElement(i)).first) : i;
    bounds[target] = hb[i] + L_->getNumEntriesInLocalRow(i) + 1;
  }
  auto graph = rcp(new CrsGraph(map, Teuchos::ArrayView<const size_t>(bounds.data(), bounds.size())));
  Teuchos::Array<GO> cols(L_->getNodeMaxNumRowEntries());
  for (LO i = 0; i < static_cast<LO>(map->getNodeNumElements()); ++i) {
    const GO gi = map->getGlobalElement(i);
    const GO row = leftJ ? J->jRow(gi).first : gi;
    size_t nnz = 0;
    L_->getGraph()->getGlobalRowCopy(gi, cols(), nnz);
    if (nnz > 0) graph->insertGlobalIndices(row, cols(0, nnz));
    graph->insertGlobalIndices(gi, Teuchos::tuple<GO>(gi));  // diagonal: identity / preconditioners
  }
  assembly_.insertHessianPattern(*graph, J);
  graph->fillComplete(map, map);
  cached = graph;
  return cached;
}

RCP<CrsMatrix> HamiltonianSystem::createHessianN() const {
  auto H = rcp(new CrsMatrix(hessianGraph(false)));
  H->fillComplete(space_->map(), space_->map());  // packed storage from the start (LocalScatter)
  return H;
}

void HamiltonianSystem::hessianN(const Vector& y, CrsMatrix& out) const {
  assembly_.evaluate(y, false, true);
  out.resumeFill();
  out.setAllToScalar(0.0);
  assembly_.addHessian(out, 1.0);
  out.fillComplete(space_->map(), space_->map());
}

void HamiltonianSystem::addLinearPart(Scalar scale, CrsMatrix& target, bool leftJ) const {
  LocalScatter& scatter = linScatter_[leftJ ? 1 : 0];
  const CrsGraph& graph = *target.getCrsGraph();
  if (!scatter.builtFor(&graph)) {  // once per target graph
    std::vector<GO> rows, cols;
    linValues_.clear();
    const auto& map = *space_->map();
    Teuchos::Array<GO> c(L_->getNodeMaxNumRowEntries());
    Teuchos::Array<Scalar> v(L_->getNodeMaxNumRowEntries());
    for (LO i = 0; i < static_cast<LO>(map.getNodeNumElements()); ++i) {
      const GO gi = map.getGlobalElement(i);
      const auto [row, sign] = leftJ ? space_->jRow(gi) : std::pair<GO, Scalar>(gi, 1.0);
      size_t nnz = 0;
      L_->getGlobalRowCopy(gi, c(), v(), nnz);
      for (size_t j = 0; j < nnz; ++j) {
        rows.push_back(row);
        cols.push_back(c[j]);
        linValues_.push_back(sign * v[j]);
      }
    }
    scatter = LocalScatter(graph, rows, cols);
    linBuf_.resize(linValues_.size());
  }
  for (size_t e = 0; e < linValues_.size(); ++e) linBuf_[e] = scale * linValues_[e];
  scatter.add(target, linBuf_.data());
}

void HamiltonianSystem::addHessian(const Vector& y, Scalar scale, CrsMatrix& target, bool leftJ) const {
  assembly_.evaluate(y, false, true);
  addLinearPart(scale, target, leftJ);
  assembly_.addHessian(target, scale, leftJ ? space_.get() : nullptr);
}

}  // namespace gphr
