#include "gphr/reduction/GalerkinRom.hpp"

#include "gphr/core/Error.hpp"

namespace gphr {

namespace {
const MultiVector& checkedBasis(const HamiltonianSystem& sys, const MultiVector& A) {
  GPHR_REQUIRE(A.getMap()->isSameAs(*sys.map()), InputError, "Galerkin ROM: the basis has ", A.getGlobalLength(),
               " rows but the system has size ", sys.space().fullDim());
  GPHR_REQUIRE(A.getNumVectors() % 2 == 0, InputError, "Galerkin ROM: the basis must have 2k columns, got ",
               A.getNumVectors());
  return A;
}
}  // namespace

GalerkinRom::GalerkinRom(RCP<const HamiltonianSystem> system, RCP<const MultiVector> A)
    : ReducedHamiltonian(reduceLinearPart(*system, checkedBasis(*system, *A)),
                         rcp(new ReducedRowKernel(system->nonlinearTermPtr(), ownedRowSample(*system, *A),
                                                  system->space().comm()))),
      sys_(system), A_(A) {
  localMap_ = rcp(new Map(A_->getNumVectors(), 0, sys_->space().comm(), Tpetra::LocallyReplicated));
  zLocal_ = rcp(new MultiVector(localMap_, 1));
}

void GalerkinRom::lift(const DenseVector& z, Vector& y) const {
  {
    auto v = zLocal_->getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (int i = 0; i < dim(); ++i) v(i, 0) = z(i);
  }
  y.multiply(Teuchos::NO_TRANS, Teuchos::NO_TRANS, 1.0, *A_, *zLocal_, 0.0);
}

DenseVector GalerkinRom::project(const Vector& y) const {
  MultiVector c(localMap_, 1);
  c.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, *A_, y, 0.0);
  auto v = c.getLocalViewHost(Tpetra::Access::ReadOnly);
  DenseVector z(dim());
  for (int i = 0; i < dim(); ++i) z(i) = v(i, 0);
  return z;
}

}  // namespace gphr
