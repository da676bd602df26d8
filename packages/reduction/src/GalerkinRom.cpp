#include "gphr/reduction/GalerkinRom.hpp"

#include "gphr/core/Error.hpp"

namespace gphr {

GalerkinRom::GalerkinRom(RCP<const HamiltonianSystem> system, RCP<const MultiVector> A) : sys_(system), A_(A) {
  GPHR_REQUIRE(A_->getMap()->isSameAs(*sys_->map()), InputError, "Galerkin ROM: the basis has ",
               A_->getGlobalLength(), " rows but the system has size ", sys_->space().fullDim());
  GPHR_REQUIRE(A_->getNumVectors() % 2 == 0, InputError, "Galerkin ROM: the basis must have 2k columns, got ",
               A_->getNumVectors());
  localMap_ = rcp(new Map(A_->getNumVectors(), 0, sys_->space().comm(), Tpetra::LocallyReplicated));
  y_ = rcp(new Vector(sys_->map()));
  g_ = rcp(new Vector(sys_->map()));
  hessN_ = sys_->createHessianN();
  HA_ = rcp(new MultiVector(sys_->map(), A_->getNumVectors()));
  zLocal_ = rcp(new MultiVector(localMap_, 1));
  AtyLocal_ = rcp(new MultiVector(localMap_, 1));
  AtHALocal_ = rcp(new MultiVector(localMap_, A_->getNumVectors()));
  MultiVector LA(sys_->map(), A_->getNumVectors());
  sys_->linearPart().apply(*A_, LA);
  Lr_ = transposeTimes(LA);
}

DenseMatrix GalerkinRom::transposeTimes(const MultiVector& X) const {
  MultiVector C(localMap_, X.getNumVectors());
  C.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, *A_, X, 0.0);
  DenseMatrix out(dim(), static_cast<int>(X.getNumVectors()));
  auto c = C.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (int j = 0; j < out.numCols(); ++j)
    for (int i = 0; i < out.numRows(); ++i) out(i, j) = c(i, j);
  return out;
}

void GalerkinRom::lift(const DenseVector& z, Vector& y) const {
  {
    auto v = zLocal_->getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (int i = 0; i < dim(); ++i) v(i, 0) = z(i);
  }
  y.multiply(Teuchos::NO_TRANS, Teuchos::NO_TRANS, 1.0, *A_, *zLocal_, 0.0);
}

DenseVector GalerkinRom::project(const Vector& y) const {
  const DenseMatrix c = transposeTimes(y);
  DenseVector z(dim());
  for (int i = 0; i < dim(); ++i) z(i) = c(i, 0);
  return z;
}

double GalerkinRom::hamiltonian(const DenseVector& z) {
  lift(z, *y_);
  return sys_->hamiltonian(*y_);
}

void GalerkinRom::gradient(const DenseVector& z, DenseVector& g) {
  lift(z, *y_);
  sys_->gradient(*y_, *g_);
  AtyLocal_->multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, *A_, *g_, 0.0);  // A^T grad H(Az)
  auto v = AtyLocal_->getLocalViewHost(Tpetra::Access::ReadOnly);
  for (int i = 0; i < dim(); ++i) g(i) = v(i, 0);
}

void GalerkinRom::addHessian(const DenseVector& z, double scale, DenseMatrix& H) {
  lift(z, *y_);
  sys_->hessianN(*y_, *hessN_);
  hessN_->apply(*A_, *HA_);
  AtHALocal_->multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, *A_, *HA_, 0.0);
  auto AtHA = AtHALocal_->getLocalViewHost(Tpetra::Access::ReadOnly);
  for (int j = 0; j < dim(); ++j)
    for (int i = 0; i < dim(); ++i) H(i, j) += scale * (Lr_(i, j) + AtHA(i, j));
}

}  // namespace gphr
