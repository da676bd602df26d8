#include "gphr/reduction/ReducedRowKernel.hpp"

#include <KokkosBlas2_gemv.hpp>
#include <KokkosBlas3_gemm.hpp>
#include <Teuchos_CommHelpers.hpp>

#include "gphr/core/Error.hpp"

namespace gphr {

namespace {
// Column-major (LayoutLeft) views of the row-major buffers: KokkosKernels is instantiated for
// LayoutLeft (and calls BLAS for host views), and a row-major M x r array is a column-major r x M one.
using ColMajor = Kokkos::View<Scalar**, Kokkos::LayoutLeft, Kokkos::HostSpace, Kokkos::MemoryUnmanaged>;
using Vec = Kokkos::View<Scalar*, Kokkos::LayoutLeft, Kokkos::HostSpace, Kokkos::MemoryUnmanaged>;
using ConstVec = Kokkos::View<const Scalar*, Kokkos::LayoutLeft, Kokkos::HostSpace, Kokkos::MemoryUnmanaged>;
}  // namespace

ReducedRowKernel::ReducedRowKernel(RCP<const RowEvaluator> term, RowSample sample, RCP<const Comm> sumOver)
    : term_(term), sample_(std::move(sample)), sumOver_(sumOver) {
  const RowSample& s = sample_;
  const int r = s.reducedDim;
  const size_t M = s.stencil.gids.size(), nr = s.rows.size();
  GPHR_REQUIRE(r >= 1, InputError, "reduced row kernel: reduced dimension ", r, " must be >= 1");
  GPHR_REQUIRE(s.stencil.numRows() == static_cast<LO>(nr) && s.weights.size() == nr, InputError,
               "reduced row kernel: ", nr, " rows but ", s.stencil.numRows(), " stencils and ", s.weights.size(),
               " weights");
  GPHR_REQUIRE(s.basisRows.size() == M * r && s.reference.size() == M, InputError,
               "reduced row kernel: basis rows / reference do not match the ", M, " stencil entries");
  // The kernel reads stencilSize() values per row: a stencil of another size (a damaged file)
  // would make it read past its row.
  for (LO i = 0; term->stencilSize() > 0 && i < s.stencil.numRows(); ++i)
    GPHR_REQUIRE(s.stencil.size(i) == term->stencilSize(), InputError, "reduced row kernel: row ", s.rows[i], " has ",
                 s.stencil.size(i), " stencil entries; the row kernel reads ", term->stencilSize());
  batch_.allocate(s.rows, s.stencil.offsets, true, true);
  // AS_ is written in full below and W_ before every read: no zero fill (GP-ADEIM builds a kernel
  // per update, and at m = 100, 2k = 400 these are 640 KB each).
  AS_ = Rows2(Kokkos::view_alloc(Kokkos::WithoutInitializing, "gphr::AS"), M, r);
  W_ = Rows2(Kokkos::view_alloc(Kokkos::WithoutInitializing, "gphr::W"), M, r);
  yref_ = HostView1("gphr::yref", M);
  u_ = HostView1("gphr::u", M);
  v0_ = HostView1("gphr::v0", M);
  v1_ = HostView1("gphr::v1", M);
  uSum_ = HostView1("gphr::uSum", M);
  hessSum_ = HostView1("gphr::hessSum", batch_.hess.extent(0));
  w_ = HostView1("gphr::w", nr);
  gRef_ = HostView1("gphr::gRef", nr);
  entryRow_ = IndexView("gphr::entryRow", M);
  for (size_t j = 0; j < M; ++j) {
    yref_(j) = s.reference[j];
    for (int c = 0; c < r; ++c) AS_(j, c) = s.basisRows[j * r + c];
  }
  for (size_t i = 0; i < nr; ++i)
    for (size_t j = s.stencil.offsets[i]; j < s.stencil.offsets[i + 1]; ++j) entryRow_(j) = static_cast<LO>(i);
  setWeights(s.weights);
  gradBuf_.resize(r);  // hessBuf_ and sumBuf_ (r x r) on first use: most kernels never assemble a Hessian
  if (s.shifted) {  // G_i(yref): the kernel at z = 0
    evaluate(DenseVector(r), false, false);
    for (size_t i = 0; i < nr; ++i) gRef_(i) = batch_.g(i);
  }
}

void ReducedRowKernel::setWeights(const std::vector<Scalar>& w) {
  GPHR_REQUIRE(w.size() == sample_.rows.size(), InputError, "reduced row kernel: ", w.size(),
               " weights given for ", sample_.rows.size(), " rows");
  sample_.weights = w;
  for (size_t i = 0; i < w.size(); ++i) w_(i) = w[i];
}

void ReducedRowKernel::evaluate(const DenseVector& z, bool withGradient, bool withHessian) {
  const int r = reducedDim();
  GPHR_REQUIRE(z.length() == r, InputError, "reduced row kernel: z has length ", z.length(), ", expected ", r);
  if (numStencilEntries() > 0) {
    // values = yref + A_S z: KokkosBlas gemv on A_S^T (column-major r x M, the same memory as the
    // row-major A_S), which is BLAS on a host build and a device kernel elsewhere.
    Kokkos::deep_copy(batch_.values, yref_);
    const ConstVec zv(z.values(), r);
    KokkosBlas::gemv("T", 1.0, basisT(), zv, 1.0, batch_.values);
  }
  RowBatch b = batch_;
  if (!withGradient) b.grad = HostView1();
  if (!withHessian) b.hess = HostView1();
  term_->evaluate(b);
}

double ReducedRowKernel::value() const {
  const auto g = batch_.g;
  const auto gRef = gRef_;
  const auto w = w_;
  // A plain loop, not Kokkos::parallel_reduce: the Serial backend keeps one process-wide scratch
  // for reductions (resized on each dispatch), and gphr query runs independent online models on
  // several threads at once. The sum is the same, in the same order, as Serial's.
  double local = 0.0;
  for (LO i = 0; i < numRows(); ++i) local += w(i) * (g(i) - gRef(i));
  if (sumOver_.is_null()) return local;
  double global = 0.0;
  Teuchos::reduceAll(*sumOver_, Teuchos::REDUCE_SUM, local, Teuchos::outArg(global));
  return global;
}

void ReducedRowKernel::weightedGradients() const {
  const auto u = u_;
  const auto grad = batch_.grad;
  const auto w = w_;
  const auto row = entryRow_;
  Kokkos::parallel_for(
      "gphr::weightedGradient", Kokkos::RangePolicy<ExecSpace>(0, numStencilEntries()),
      KOKKOS_LAMBDA(const size_t j) { u(j) = w(row(j)) * grad(j); });
}

void ReducedRowKernel::weightedHessianBlocks(const HostView1& hessians) const {
  // W rows of row i: w_i Hess G_i A_Si (s x r), one row of G per Kokkos index.
  const int r = reducedDim();
  const auto AS = AS_;
  const auto W = W_;
  const auto hess = hessians;
  const auto off = batch_.offsets;
  const auto hoff = batch_.hessOffsets;
  const auto w = w_;
  Kokkos::parallel_for(
      "gphr::weightedHessianBlocks", Kokkos::RangePolicy<ExecSpace>(0, numRows()), KOKKOS_LAMBDA(const LO i) {
        const size_t j0 = off(i), s = off(i + 1) - j0;
        const Scalar* h = &hess(hoff(i));
        for (size_t a = 0; a < s; ++a)
          for (int c = 0; c < r; ++c) {
            Scalar sum = 0.0;
            for (size_t b = 0; b < s; ++b) sum += h[a * s + b] * AS(j0 + b, c);
            W(j0 + a, c) = w(i) * sum;
          }
      });
}

// Serial loops: several stencil entries share a slot, and the slots are few (classic DEIM's m).
void ReducedRowKernel::entryGradients(const std::vector<int>& entrySlot, int numSlots, Scalar* out) const {
  weightedGradients();
  std::fill(out, out + numSlots, 0.0);
  for (size_t j = 0; j < entrySlot.size(); ++j)
    if (entrySlot[j] >= 0) out[entrySlot[j]] += u_(j);
}

void ReducedRowKernel::entryHessianRows(const std::vector<int>& entrySlot, int numSlots, Scalar* out) const {
  weightedHessianBlocks(batch_.hess);
  const int r = reducedDim();
  std::fill(out, out + static_cast<size_t>(numSlots) * r, 0.0);
  for (size_t j = 0; j < entrySlot.size(); ++j)
    if (entrySlot[j] >= 0)
      for (int c = 0; c < r; ++c) out[static_cast<size_t>(entrySlot[j]) * r + c] += W_(j, c);
}

void ReducedRowKernel::reduceToGradient(const HostView1& u, DenseVector& g, double scale) const {
  const int r = reducedDim();
  const size_t M = numStencilEntries();
  // A_S^T u: AS_ row-major (M x r) is A_S^T column-major (r x M).
  std::fill(gradBuf_.begin(), gradBuf_.end(), 0.0);
  if (M > 0) KokkosBlas::gemv("N", 1.0, basisT(), ConstVec(u.data(), M), 0.0, Vec(gradBuf_.data(), r));
  if (!sumOver_.is_null()) {
    if (sumBuf_.size() < static_cast<size_t>(r)) sumBuf_.resize(r);
    Teuchos::reduceAll(*sumOver_, Teuchos::REDUCE_SUM, r, gradBuf_.data(), sumBuf_.data());
    std::copy(sumBuf_.begin(), sumBuf_.begin() + r, gradBuf_.begin());
  }
  for (int c = 0; c < r; ++c) g(c) += scale * gradBuf_[c];
}

void ReducedRowKernel::addGradient(DenseVector& g, double scale) const {
  weightedGradients();
  reduceToGradient(u_, g, scale);
}

void ReducedRowKernel::stencilValues(const DenseVector& z, HostView1 out) const {
  GPHR_REQUIRE(z.length() == reducedDim(), InputError, "reduced row kernel: z has length ", z.length(),
               ", expected ", reducedDim());
  if (numStencilEntries() > 0) KokkosBlas::gemv("T", 1.0, basisT(), ConstVec(z.values(), reducedDim()), 0.0, out);
}

void ReducedRowKernel::setZ0(const DenseVector& z0) {
  bool sameZ0 = haveZ0_;
  for (int i = 0; i < z0.length() && sameZ0; ++i) sameZ0 = z0(i) == z0_(i);
  if (sameZ0) return;
  stencilValues(z0, v0_);
  if (z0_.length() != z0.length()) z0_.size(z0.length());
  z0_.assign(z0);
  haveZ0_ = true;
}

void ReducedRowKernel::evaluateAtNode(double s, const RowBatch& b) {
  const auto v0 = v0_, v1 = v1_, yref = yref_, values = batch_.values;
  Kokkos::parallel_for(
      "gphr::nodeValues", Kokkos::RangePolicy<ExecSpace>(0, numStencilEntries()),
      KOKKOS_LAMBDA(const size_t j) { values(j) = yref(j) + (1.0 - s) * v0(j) + s * v1(j); });
  term_->evaluate(b);
}

void ReducedRowKernel::addAveragedGradient(const DenseVector& z0, const DenseVector& z1,
                                           const std::vector<double>& nodes, const std::vector<double>& weights,
                                           DenseVector& g, double scale) {
  GPHR_REQUIRE(nodes.size() == weights.size() && !nodes.empty(), InputError, "reduced row kernel: ", nodes.size(),
               " quadrature nodes and ", weights.size(), " weights");
  setZ0(z0);
  stencilValues(z1, v1_);
  const size_t M = numStencilEntries();
  const auto uSum = uSum_, grad = batch_.grad, w = w_;
  const auto row = entryRow_;
  RowBatch b = batch_;
  b.hess = HostView1();
  for (size_t q = 0; q < nodes.size(); ++q) {
    const double wq = weights[q];
    evaluateAtNode(nodes[q], b);
    const bool first = q == 0;
    Kokkos::parallel_for(
        "gphr::nodeGradientSum", Kokkos::RangePolicy<ExecSpace>(0, M), KOKKOS_LAMBDA(const size_t j) {
          uSum(j) = (first ? 0.0 : uSum(j)) + wq * w(row(j)) * grad(j);
        });
  }
  reduceToGradient(uSum_, g, scale);
}

void ReducedRowKernel::addAveragedHessian(const DenseVector& z0, const DenseVector& z1,
                                          const std::vector<double>& nodes, const std::vector<double>& coefficients,
                                          DenseMatrix& H, double scale) {
  GPHR_REQUIRE(nodes.size() == coefficients.size() && !nodes.empty(), InputError, "reduced row kernel: ",
               nodes.size(), " quadrature nodes and ", coefficients.size(), " coefficients");
  GPHR_REQUIRE(batch_.hess.extent(0) > 0 || numRows() == 0, InputError,
               "reduced row kernel: averaged Hessian without Hessian storage");
  setZ0(z0);
  stencilValues(z1, v1_);
  const size_t Mh = hessSum_.extent(0);
  const auto hess = batch_.hess, hessSum = hessSum_;
  for (size_t q = 0; q < nodes.size(); ++q) {
    const double c = coefficients[q];
    evaluateAtNode(nodes[q], batch_);
    const bool first = q == 0;
    Kokkos::parallel_for(
        "gphr::nodeHessianSum", Kokkos::RangePolicy<ExecSpace>(0, Mh),
        KOKKOS_LAMBDA(const size_t j) { hessSum(j) = (first ? 0.0 : hessSum(j)) + c * hess(j); });
  }
  weightedHessianBlocks(hessSum_);
  addBlockProduct(H, scale);
}

void ReducedRowKernel::addHessian(DenseMatrix& H, double scale) const {
  weightedHessianBlocks(batch_.hess);
  addBlockProduct(H, scale);
}

void ReducedRowKernel::addBlockProduct(DenseMatrix& H, double scale) const {
  const int r = reducedDim();
  const size_t M = numStencilEntries();
  // A_S^T W: both row-major M x r, i.e. column-major r x M: (A_S^T)(W^T)^T.
  hessBuf_.assign(static_cast<size_t>(r) * r, 0.0);
  if (M > 0)
    KokkosBlas::gemm("N", "T", 1.0, basisT(), ColMajor(W_.data(), r, M), 0.0, ColMajor(hessBuf_.data(), r, r));
  if (!sumOver_.is_null()) {
    sumBuf_.resize(hessBuf_.size());
    Teuchos::reduceAll(*sumOver_, Teuchos::REDUCE_SUM, r * r, hessBuf_.data(), sumBuf_.data());
    hessBuf_.swap(sumBuf_);
  }
  for (int j = 0; j < r; ++j)
    for (int i = 0; i < r; ++i) H(i, j) += scale * hessBuf_[i + static_cast<size_t>(r) * j];
}

void ReducedRowKernel::reducedJacobian(Scalar* out, size_t ld) const {
  const int r = reducedDim();
  const size_t stride = ld == 0 ? static_cast<size_t>(r) : ld;
  GPHR_REQUIRE(stride >= static_cast<size_t>(r), InputError, "reduced Jacobian: row stride ", ld, " < 2k = ", r);
  const auto AS = AS_;
  const auto grad = batch_.grad;
  const auto off = batch_.offsets;
  Kokkos::parallel_for(
      "gphr::reducedJacobianRows", Kokkos::RangePolicy<ExecSpace>(0, numRows()), KOKKOS_LAMBDA(const LO i) {
        // Row i = sum over its stencil entries j of grad_j A_S(j, :): axpys along the contiguous
        // basis rows (the sum over j is short; the loop over the 2k columns vectorizes).
        Scalar* __restrict row = out + static_cast<size_t>(i) * stride;
        for (int c = 0; c < r; ++c) row[c] = 0.0;
        for (size_t j = off(i); j < off(i + 1); ++j) {
          const Scalar g = grad(j);
          const Scalar* __restrict a = &AS(j, 0);
          for (int c = 0; c < r; ++c) row[c] += g * a[c];
        }
      });
}

void ReducedRowKernel::rowValues(Scalar* out) const {
  for (LO i = 0; i < numRows(); ++i) out[i] = batch_.g(i) - gRef_(i);
}

RowSample ownedRowSample(const HamiltonianSystem& system, const MultiVector& A) {
  const NonlinearTerm& term = system.nonlinearTerm();
  const RCP<const Map> overlap = term.jacobianGraph()->getColMap();  // owned + ghost state entries
  const Import importer(system.map(), overlap);
  MultiVector Aov(overlap, A.getNumVectors());
  Aov.doImport(A, importer, Tpetra::INSERT);
  Vector refOv(overlap);
  if (!system.reference().is_null()) refOv.doImport(*system.reference(), importer, Tpetra::INSERT);
  RowSample s;
  s.reducedDim = static_cast<int>(A.getNumVectors());
  s.shifted = !system.reference().is_null();
  s.stencil = term.stencil();
  const LO nr = s.stencil.numRows();
  for (LO i = 0; i < nr; ++i) s.rows.push_back(term.rowMap()->getGlobalElement(i));
  auto v = term.weights()->getLocalViewHost(Tpetra::Access::ReadOnly);
  for (LO i = 0; i < nr; ++i) s.weights.push_back(v(i, 0));
  auto a = Aov.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto y = refOv.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (GO gid : s.stencil.gids) {
    const LO l = overlap->getLocalElement(gid);
    for (int c = 0; c < s.reducedDim; ++c) s.basisRows.push_back(a(l, c));
    s.reference.push_back(y(l, 0));
  }
  return s;
}

}  // namespace gphr
