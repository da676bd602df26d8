#include "gphr/reduction/ReducedHamiltonian.hpp"

#include "gphr/core/Error.hpp"

#include <algorithm>

// Teuchos::BLAS (Trilinos 13.2) has no SYMV; BLAS itself is linked through Teuchos.
extern "C" void dsymv_(const char* uplo, const int* n, const double* alpha, const double* a, const int* lda,
                       const double* x, const int* incx, const double* beta, double* y, const int* incy);

namespace gphr {

namespace {
// out = L z for the symmetric L_r (symmetric to the last bit, see reduceLinearPart). SYMV reads
// one triangle: half the memory traffic of GEMV, which is what bounds this product once per
// Newton iteration (L_r is 2k x 2k: 1.3 MB at 2k = 400, beyond the L2 cache).
void symmetricProduct(const DenseMatrix& L, const double* z, double* out) {
  const int n = L.numRows(), lda = L.stride(), one = 1;
  const double alpha = 1.0, beta = 0.0;
  if (n > 0) dsymv_("U", &n, &alpha, L.values(), &lda, z, &one, &beta, out, &one);
}
}  // namespace

namespace {
// L_r = A^T (L A) a block of kLinearPartColumns columns at a time: L A whole is a rows x 2k array
// (42 MB per rank for the SWE 256^2's 2k = 40 on one rank), above glibc's largest mmap threshold
// (32 MB), so each call mapped it afresh and the kernel zeroed its pages. The model file's
// interpolation projects once per node: on one rank its system time fell from 3.4 to 2.2 s (57
// projections, SWE 256^2). A block of 8 columns is reused from the heap.
constexpr int kLinearPartColumns = 8;
}  // namespace

ReducedLinearPart reduceLinearPart(const HamiltonianSystem& system, const MultiVector& A) {
  const int r = static_cast<int>(A.getNumVectors());
  auto local = rcp(new Map(r, 0, system.space().comm(), Tpetra::LocallyReplicated));
  MultiVector Lr(local, r), fr(local, 1);
  for (int j0 = 0; j0 < r; j0 += kLinearPartColumns) {
    const Teuchos::Range1D cols(j0, std::min(r, j0 + kLinearPartColumns) - 1);
    const auto Aj = A.subView(cols);
    MultiVector LAj(system.map(), cols.size());
    system.linearPart().apply(*Aj, LAj);
    Lr.subViewNonConst(cols)->multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, A, LAj, 0.0);
  }
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
  if (lz_.length() != dim()) lz_.size(dim());
  symmetricProduct(linear_.L, z.values(), lz_.values());
  double h = linear_.c;
  for (int i = 0; i < dim(); ++i) h += z(i) * (0.5 * lz_(i) + linear_.f(i));
  return h + rows_->value();
}

void ReducedHamiltonian::gradient(const DenseVector& z, DenseVector& g) {
  GPHR_REQUIRE(z.length() == dim() && g.length() == dim(), InputError, "reduced Hamiltonian: gradient of a ",
               z.length(), "-vector into a ", g.length(), "-vector (need ", dim(), ")");
  evaluateAt(z);
  symmetricProduct(linear_.L, z.values(), g.values());
  g += linear_.f;
  rows_->addGradient(g, 1.0);
}

bool ReducedHamiltonian::averagedGradient(const DenseVector& z0, const DenseVector& z1, const QuadratureRule& rule,
                                          DenseVector& gbar) {
  const int n = dim();
  GPHR_REQUIRE(z0.length() == n && z1.length() == n && gbar.length() == n, InputError,
               "reduced Hamiltonian: averaged gradient of ", z0.length(), "- and ", z1.length(), "-vectors into a ",
               gbar.length(), "-vector (need ", n, ")");
  if (zbar_.length() != n) zbar_.size(n);
  zbar_.putScalar(0.0);
  double wsum = 0.0;
  for (int q = 0; q < rule.size(); ++q) {
    const double s = rule.nodes[q], w = rule.weights[q];
    wsum += w;
    for (int i = 0; i < n; ++i) zbar_(i) += w * ((1.0 - s) * z0(i) + s * z1(i));
  }
  symmetricProduct(linear_.L, zbar_.values(), gbar.values());
  for (int i = 0; i < n; ++i) gbar(i) += wsum * linear_.f(i);
  rows_->addAveragedGradient(z0, z1, rule.nodes, rule.weights, gbar, 1.0);
  haveLast_ = false;  // the kernel now holds the last node's evaluation, without Hessian
  return true;
}

bool ReducedHamiltonian::addAveragedHessian(const DenseVector& z0, const DenseVector& z1, const QuadratureRule& rule,
                                            double scale, DenseMatrix& H) {
  const int n = dim();
  GPHR_REQUIRE(z0.length() == n && z1.length() == n && H.numRows() == n && H.numCols() == n, InputError,
               "reduced Hamiltonian: averaged Hessian of ", z0.length(), "- and ", z1.length(), "-vectors into a ",
               H.numRows(), " x ", H.numCols(), " matrix (need ", n, ")");
  std::vector<double> coef(rule.size());
  double csum = 0.0;
  for (int q = 0; q < rule.size(); ++q) csum += coef[q] = rule.weights[q] * rule.nodes[q];
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) H(i, j) += scale * csum * linear_.L(i, j);
  rows_->addAveragedHessian(z0, z1, rule.nodes, coef, H, scale);
  haveLast_ = false;  // the kernel now holds the last node's evaluation
  return true;
}

void ReducedHamiltonian::addHessian(const DenseVector& z, double scale, DenseMatrix& H) {
  evaluateAt(z);
  for (int j = 0; j < dim(); ++j)
    for (int i = 0; i < dim(); ++i) H(i, j) += scale * linear_.L(i, j);
  rows_->addHessian(H, scale);
}

}  // namespace gphr
