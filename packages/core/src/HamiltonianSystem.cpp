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

RCP<const CrsGraph> HamiltonianSystem::hessianGraph(bool withCanonical) const {
  auto& cached = hessGraph_[withCanonical ? 1 : 0];
  if (!cached.is_null()) return cached;
  const auto& map = space_->map();
  // Static profile: capacity = entries of L + diagonal + partner + the stencil bound.
  std::vector<size_t> bounds = assembly_.hessianRowBounds();
  for (LO i = 0; i < static_cast<LO>(bounds.size()); ++i) bounds[i] += L_->getNumEntriesInLocalRow(i) + 2;
  auto graph = rcp(new CrsGraph(map, Teuchos::ArrayView<const size_t>(bounds.data(), bounds.size())));
  Teuchos::Array<GO> cols(L_->getNodeMaxNumRowEntries());
  for (LO i = 0; i < static_cast<LO>(map->getNodeNumElements()); ++i) {
    const GO gi = map->getGlobalElement(i);
    size_t nnz = 0;
    L_->getGraph()->getGlobalRowCopy(gi, cols(), nnz);
    if (nnz > 0) graph->insertGlobalIndices(gi, cols(0, nnz));
    graph->insertGlobalIndices(gi, Teuchos::tuple<GO>(gi));  // diagonal, for preconditioners
    if (withCanonical) {
      const GO partner = gi < space_->n() ? gi + space_->n() : gi - space_->n();
      graph->insertGlobalIndices(gi, Teuchos::tuple<GO>(partner));
    }
  }
  assembly_.insertHessianPattern(*graph);
  graph->fillComplete(map, map);
  cached = graph;
  return cached;
}

RCP<CrsMatrix> HamiltonianSystem::createHessianN() const {
  return rcp(new CrsMatrix(hessianGraph(false)));
}

void HamiltonianSystem::hessianN(const Vector& y, CrsMatrix& out) const {
  assembly_.evaluate(y, false, true);
  out.resumeFill();
  out.setAllToScalar(0.0);
  assembly_.addHessian(out, 1.0);
  out.fillComplete(space_->map(), space_->map());
}

void HamiltonianSystem::addLinearPart(Scalar scale, CrsMatrix& target) const {
  const auto& map = space_->map();
  const size_t maxNnz = L_->getNodeMaxNumRowEntries();
  Teuchos::Array<GO> cols(maxNnz);
  Teuchos::Array<Scalar> vals(maxNnz);
  for (LO i = 0; i < static_cast<LO>(map->getNodeNumElements()); ++i) {
    const GO gi = map->getGlobalElement(i);
    size_t nnz = 0;
    L_->getGlobalRowCopy(gi, cols(), vals(), nnz);
    for (size_t j = 0; j < nnz; ++j) vals[j] *= scale;
    if (nnz > 0) target.sumIntoGlobalValues(gi, cols(0, nnz), vals(0, nnz));
  }
}

void HamiltonianSystem::addHessian(const Vector& y, Scalar scale, CrsMatrix& target) const {
  assembly_.evaluate(y, false, true);
  addLinearPart(scale, target);
  assembly_.addHessian(target, scale);
}

}  // namespace gphr
