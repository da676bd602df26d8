#include "gphr/reduction/ReducedHamiltonian.hpp"

#include "gphr/core/Error.hpp"

namespace gphr {

ReducedLinearPart reduceLinearPart(const HamiltonianSystem& system, const MultiVector& A) {
  const int r = static_cast<int>(A.getNumVectors());
  auto local = rcp(new Map(r, 0, system.space().comm(), Tpetra::LocallyReplicated));
  MultiVector LA(system.map(), r), Lr(local, r), fr(local, 1);
  system.linearPart().apply(A, LA);
  Lr.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, A, LA, 0.0);
  fr.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, A, system.linearForce(), 0.0);
  ReducedLinearPart out;
  out.L.shape(r, r);
  out.f.size(r);
  out.c = system.constant();
  auto l = Lr.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto f = fr.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (int j = 0; j < r; ++j) {
    out.f(j) = f(j, 0);
    for (int i = 0; i < r; ++i) out.L(i, j) = 0.5 * (l(i, j) + l(j, i));  // symmetric to the last bit
  }
  return out;
}

ReducedHamiltonian::ReducedHamiltonian(ReducedLinearPart linear, RCP<ReducedRowKernel> rows)
    : linear_(std::move(linear)), rows_(rows), lastZ_(linear_.L.numRows()) {
  GPHR_REQUIRE(rows_->reducedDim() == linear_.L.numRows(), InputError, "reduced Hamiltonian: the row sample has ",
               rows_->reducedDim(), " reduced coordinates but L_r is ", linear_.L.numRows(), " x ",
               linear_.L.numRows());
}

void ReducedHamiltonian::replaceRows(RCP<ReducedRowKernel> rows) {
  GPHR_REQUIRE(rows->reducedDim() == dim(), InputError, "reduced Hamiltonian: a row sample of ", rows->reducedDim(),
               " reduced coordinates cannot replace one of ", dim());
  rows_ = rows;
  haveLast_ = false;
}

// Gradient and Hessian come from one kernel evaluation per point: the kernel always computes
// both (s^2 numbers per row, cheap next to the GEMM of addHessian) and is rerun only when z moves.
void ReducedHamiltonian::evaluateAt(const DenseVector& z) {
  if (haveLast_) {
    bool same = true;
    for (int i = 0; i < z.length() && same; ++i) same = z(i) == lastZ_(i);
    if (same) return;
  }
  rows_->evaluate(z, true, true);
  lastZ_.assign(z);
  haveLast_ = true;
  ++evaluations_;
}

double ReducedHamiltonian::hamiltonian(const DenseVector& z) {
  evaluateAt(z);
  double h = linear_.c;
  for (int i = 0; i < dim(); ++i) {
    double lz = 0.0;
    for (int j = 0; j < dim(); ++j) lz += linear_.L(i, j) * z(j);
    h += z(i) * (0.5 * lz + linear_.f(i));
  }
  return h + rows_->value();
}

void ReducedHamiltonian::gradient(const DenseVector& z, DenseVector& g) {
  evaluateAt(z);
  g.multiply(Teuchos::NO_TRANS, Teuchos::NO_TRANS, 1.0, linear_.L, z, 0.0);
  g += linear_.f;
  rows_->addGradient(g, 1.0);
}

void ReducedHamiltonian::addHessian(const DenseVector& z, double scale, DenseMatrix& H) {
  evaluateAt(z);
  for (int j = 0; j < dim(); ++j)
    for (int i = 0; i < dim(); ++i) H(i, j) += scale * linear_.L(i, j);
  rows_->addHessian(H, scale);
}

}  // namespace gphr
