#include "gphr/reduction/ReducedHamiltonian.hpp"

#include "gphr/core/Error.hpp"

#include <Teuchos_BLAS.hpp>
#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <vector>

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

// L_r = A^T (L A), a block of kLinearPartColumns columns of L A at a time: L A whole is a rows x 2k
// array (42 MB per rank for the SWE 256^2's 2k = 40 on one rank), above glibc's largest mmap
// threshold (32 MB), so each call mapped it afresh and the kernel zeroed its pages. The model
// file's interpolation projects once per node: on one rank its system time fell from 3.4 to 2.2 s
// (57 projections, SWE 256^2). A block of 8 columns is reused from the heap.
constexpr int kLinearPartColumns = 8;

// Block j0 of L_r's upper triangle: rows 0 .. j0 + nb - 1 of columns j0 .. j0 + nb - 1, this
// rank's rows only (BLAS GEMM on the local arrays; the ranks' sums are added by the caller).
// L_r is symmetric, so the blocks below the diagonal are not formed: (r/8 + 1) / (2 r/8) of the
// flops and packing of the whole A^T (L A) (0.6 at 2k = 40).
void upperBlock(const MultiVector& A, const MultiVector& LAj, int j0, std::vector<double>& upper) {
  const int rows = static_cast<int>(A.getLocalLength()), r = static_cast<int>(A.getNumVectors());
  const int nb = static_cast<int>(LAj.getNumVectors());
  if (rows == 0) return;
  auto a = A.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto b = LAj.getLocalViewHost(Tpetra::Access::ReadOnly);
  Teuchos::BLAS<int, double> blas;
  blas.GEMM(Teuchos::TRANS, Teuchos::NO_TRANS, j0 + nb, nb, rows, 1.0, a.data(), static_cast<int>(A.getStride()),
            b.data(), static_cast<int>(LAj.getStride()), 0.0, upper.data() + static_cast<size_t>(j0) * r, r);
}
}  // namespace

ReducedLinearPart reduceLinearPart(const HamiltonianSystem& system, const MultiVector& basis) {
  // BLAS reads A by one leading dimension: a basis of scattered columns is copied once.
  const RCP<const MultiVector> copy =
      basis.isConstantStride() ? Teuchos::null : rcp(new MultiVector(basis, Teuchos::Copy));
  const MultiVector& A = copy.is_null() ? basis : *copy;
  const int r = static_cast<int>(A.getNumVectors());
  const int rows = static_cast<int>(A.getLocalLength());
  // Local sums: L_r's upper triangle (column-major r x r), then f_r = A^T f; one all-reduce.
  std::vector<double> local(static_cast<size_t>(r) * r + r, 0.0), global(local.size());
  MultiVector LA(system.map(), std::max(1, std::min(r, kLinearPartColumns)));
  for (int j0 = 0; j0 < r; j0 += kLinearPartColumns) {
    const int nb = std::min(r, j0 + kLinearPartColumns) - j0;
    const auto LAj = LA.subViewNonConst(Teuchos::Range1D(0, nb - 1));
    system.linearPart().apply(*A.subView(Teuchos::Range1D(j0, j0 + nb - 1)), *LAj);
    upperBlock(A, *LAj, j0, local);
  }
  if (rows > 0 && r > 0) {
    auto a = A.getLocalViewHost(Tpetra::Access::ReadOnly);
    auto f = system.linearForce().getLocalViewHost(Tpetra::Access::ReadOnly);
    Teuchos::BLAS<int, double>().GEMV(Teuchos::TRANS, rows, r, 1.0, a.data(), static_cast<int>(A.getStride()),
                                      f.data(), 1, 0.0, local.data() + static_cast<size_t>(r) * r, 1);
  }
  Teuchos::reduceAll(*system.space().comm(), Teuchos::REDUCE_SUM, static_cast<int>(local.size()), local.data(),
                     global.data());
  ReducedLinearPart out;
  out.L.shape(r, r);
  out.f.size(r);
  out.c = system.constant();
  for (int j = 0; j < r; ++j) {
    out.f(j) = global[static_cast<size_t>(r) * r + j];
    for (int i = 0; i <= j; ++i)  // the upper triangle mirrored: symmetric to the last bit
      out.L(i, j) = out.L(j, i) = global[static_cast<size_t>(j) * r + i];
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
