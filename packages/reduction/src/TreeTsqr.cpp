#include "gphr/reduction/TreeTsqr.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_LAPACK.hpp>

#include <algorithm>

#include "gphr/core/Error.hpp"

// LAPACK's compact-WY QR and triangle-pentagonal QR (3.4 on): Teuchos::LAPACK (Trilinos 13.2)
// wraps neither.
extern "C" {
void dgeqrt_(const int* m, const int* n, const int* nb, double* a, const int* lda, double* t, const int* ldt,
             double* work, int* info);
void dgemqrt_(const char* side, const char* trans, const int* m, const int* n, const int* k, const int* nb,
              const double* v, const int* ldv, const double* t, const int* ldt, double* c, const int* ldc,
              double* work, int* info);
void dtpqrt_(const int* m, const int* n, const int* l, const int* nb, double* a, const int* lda, double* b,
             const int* ldb, double* t, const int* ldt, double* work, int* info);
void dtpmqrt_(const char* side, const char* trans, const int* m, const int* n, const int* k, const int* l,
              const int* nb, const double* v, const int* ldv, const double* t, const int* ldt, double* a,
              const int* lda, double* b, const int* ldb, double* work, int* info);
}

namespace gphr {

namespace {
constexpr int kPanel = 32;  // GEQRT's and TPQRT's panel width (LAPACK's usual block); T is nb x n
}

HouseholderQr::HouseholderQr(int m, int n, std::vector<double> a, int chunkRows)
    : m_(m), n_(n), nb_(std::max(1, std::min(kPanel, std::min(m, n)))), a_(std::move(a)) {
  GPHR_REQUIRE(m >= 0 && n >= 0 && chunkRows >= 1 && a_.size() >= static_cast<size_t>(m) * n, InputError,
               "Householder QR: a ", m, " x ", n, " block in ", a_.size(), " numbers, chunks of ", chunkRows,
               " rows (need chunks of at least 1 row and m n numbers)");
  if (k() == 0) return;
  // A block with fewer rows than columns is one chunk (its R a trapezoid); otherwise the first chunk
  // holds at least n rows, so that its R is the n x n triangle TPQRT takes on top.
  const int r0 = m_ <= n_ ? m_ : std::min(m_, std::max(chunkRows, n_));
  start_ = {0, r0};
  while (start_.back() < m_) start_.push_back(std::min(m_, start_.back() + chunkRows));
  t_.assign(static_cast<size_t>(nb_) * n_ * chunks(), 0.0);
  std::vector<double> work(static_cast<size_t>(nb_) * n_);
  int info = 0;
  dgeqrt_(&r0, &n_, &nb_, a_.data(), &m_, t(0), &nb_, work.data(), &info);
  GPHR_REQUIRE(info == 0, SolverError, "Householder QR: LAPACK GEQRT of ", r0, " x ", n_, " failed (info = ", info,
               ")");
  if (chunks() == 1) return;
  top_.assign(static_cast<size_t>(n_) * n_, 0.0);
  for (int j = 0; j < n_; ++j)
    std::copy_n(a_.begin() + static_cast<size_t>(m_) * j, j + 1, top_.begin() + static_cast<size_t>(n_) * j);
  const int l = 0;  // each further chunk is a full rectangle below the triangle
  for (int c = 1; c < chunks(); ++c) {
    const int rc = start_[c + 1] - start_[c];
    dtpqrt_(&rc, &n_, &l, &nb_, top_.data(), &n_, a_.data() + start_[c], &m_, t(c), &nb_, work.data(), &info);
    GPHR_REQUIRE(info == 0, SolverError, "Householder QR: LAPACK TPQRT of rows ", start_[c], " .. ", start_[c + 1],
                 " (", n_, " columns) failed (info = ", info, ")");
  }
}

std::vector<double> HouseholderQr::releaseStorage() {
  std::vector<double> a = std::move(a_);
  *this = HouseholderQr();
  return a;
}

std::vector<double> HouseholderQr::r() const {
  const int kk = k();
  std::vector<double> R(static_cast<size_t>(kk) * n_, 0.0);
  const double* src = top_.empty() ? a_.data() : top_.data();
  const size_t lds = top_.empty() ? static_cast<size_t>(m_) : static_cast<size_t>(n_);
  for (int j = 0; j < n_; ++j)
    for (int i = 0; i < std::min(kk, j + 1); ++i) R[i + static_cast<size_t>(kk) * j] = src[i + lds * j];
  return R;
}

std::vector<double> HouseholderQr::applyQ(const std::vector<double>& C, int cols) const {
  std::vector<double> out(static_cast<size_t>(m_) * cols);
  applyQInto(C, cols, out.data(), std::max(m_, 1));
  return out;
}

// Q = Q_0 Q_1 ... Q_last (Q_0 on the first chunk's rows, Q_c on the R's n rows and chunk c's):
// Q [C; 0] applies Q_last first, to C on top and zeros in the chunk, down to Q_0.
void HouseholderQr::applyQInto(const std::vector<double>& C, int cols, double* out, int ldo) const {
  const int kk = k();
  GPHR_REQUIRE(ldo >= std::max(m_, 1) && cols >= 0 && C.size() >= static_cast<size_t>(kk) * cols, InputError,
               "Householder QR: Q [C; 0] of ", m_, " x ", cols, " into leading dimension ", ldo, " from ", C.size(),
               " numbers");
  for (int j = 0; j < cols; ++j) {
    double* col = out + static_cast<size_t>(ldo) * j;
    std::fill(col + kk, col + m_, 0.0);
  }
  if (kk == 0 || cols == 0) return;  // Q [C; 0] is the zeros just written
  std::vector<double> top(C.begin(), C.begin() + static_cast<size_t>(kk) * cols);
  std::vector<double> work(static_cast<size_t>(nb_) * cols);
  int info = 0;
  const int l = 0;
  for (int c = chunks() - 1; c >= 1; --c) {
    const int rc = start_[c + 1] - start_[c];
    dtpmqrt_("L", "N", &rc, &cols, &n_, &l, &nb_, a_.data() + start_[c], &m_, t(c), &nb_, top.data(), &kk,
             out + start_[c], &ldo, work.data(), &info);
    GPHR_REQUIRE(info == 0, SolverError, "Householder QR: LAPACK TPMQRT on rows ", start_[c], " .. ", start_[c + 1],
                 " failed (info = ", info, ")");
  }
  for (int j = 0; j < cols; ++j)
    std::copy_n(top.begin() + static_cast<size_t>(kk) * j, kk, out + static_cast<size_t>(ldo) * j);
  dgemqrt_("L", "N", &start_[1], &cols, &kk, &nb_, a_.data(), &m_, t(0), &nb_, out, &ldo, work.data(), &info);
  GPHR_REQUIRE(info == 0, SolverError, "Householder QR: LAPACK GEMQRT on ", start_[1], " x ", cols,
               " failed (info = ", info, ")");
}

TriangleStackQr::TriangleStackQr(int n, std::vector<double> top, int kb, std::vector<double> below)
    : n_(n), kb_(kb), nb_(std::max(1, std::min(kPanel, n))), a_(std::move(top)), v_(std::move(below)) {
  GPHR_REQUIRE(n >= 0 && kb >= 0 && kb <= n && a_.size() == static_cast<size_t>(n) * n &&
                   v_.size() == static_cast<size_t>(kb) * n,
               InputError, "triangle-stack QR: a ", n, " x ", n, " triangle on a ", kb, " x ", n,
               " trapezoid (need kb <= n and matching arrays)");
  t_.assign(static_cast<size_t>(nb_) * std::max(n, 1), 0.0);
  if (n == 0 || kb == 0) return;  // [T; nothing]: R = T, Q = I
  std::vector<double> work(static_cast<size_t>(nb_) * n);
  int info = 0;
  dtpqrt_(&kb_, &n_, &kb_, &nb_, a_.data(), &n_, v_.data(), &kb_, t_.data(), &nb_, work.data(), &info);
  GPHR_REQUIRE(info == 0, SolverError, "triangle-stack QR: LAPACK TPQRT of ", n, " + ", kb, " rows failed (info = ",
               info, ")");
}

std::vector<double> TriangleStackQr::r() const {
  std::vector<double> R(a_.size(), 0.0);
  for (int j = 0; j < n_; ++j)
    for (int i = 0; i <= j; ++i) R[i + static_cast<size_t>(n_) * j] = a_[i + static_cast<size_t>(n_) * j];
  return R;
}

std::vector<double> TriangleStackQr::applyQ(const std::vector<double>& C, int cols) const {
  std::vector<double> top(C.begin(), C.begin() + static_cast<size_t>(n_) * cols), bottom(static_cast<size_t>(kb_) * cols, 0.0);
  if (kb_ > 0 && cols > 0) {
    std::vector<double> work(static_cast<size_t>(nb_) * cols);
    int info = 0;
    dtpmqrt_("L", "N", &kb_, &cols, &n_, &kb_, &nb_, v_.data(), &kb_, t_.data(), &nb_, top.data(), &n_, bottom.data(),
             &kb_, work.data(), &info);
    GPHR_REQUIRE(info == 0, SolverError, "triangle-stack QR: LAPACK TPMQRT on ", n_ + kb_, " x ", cols,
                 " failed (info = ", info, ")");
  }
  std::vector<double> out(static_cast<size_t>(rows()) * cols);
  for (int j = 0; j < cols; ++j) {
    std::copy_n(top.begin() + static_cast<size_t>(n_) * j, n_, out.begin() + static_cast<size_t>(rows()) * j);
    std::copy_n(bottom.begin() + static_cast<size_t>(kb_) * j, kb_, out.begin() + n_ + static_cast<size_t>(rows()) * j);
  }
  return out;
}

namespace {
// Rows [r0, r1) of the column-major m x cols block a.
std::vector<double> rowBlock(const std::vector<double>& a, int m, int cols, int r0, int r1) {
  std::vector<double> out(static_cast<size_t>(r1 - r0) * cols);
  for (int j = 0; j < cols; ++j)
    std::copy(a.begin() + r0 + static_cast<size_t>(m) * j, a.begin() + r1 + static_cast<size_t>(m) * j,
              out.begin() + static_cast<size_t>(r1 - r0) * j);
  return out;
}
}  // namespace

std::vector<double> TreeTsqr::reduce(std::vector<double> R, int k, int* rootRows) {
  const int p = comm_.getSize(), me = comm_.getRank();
  levels_.clear();
  parent_ = -1;
  for (int s = 1; s < p; s *= 2) {
    if (me % (2 * s) == s) {  // send up and leave the reduction
      parent_ = me - s, sent_ = k;
      Teuchos::send(comm_, 1, &k, parent_);
      if (k > 0) Teuchos::send(comm_, k * n_, R.data(), parent_);
      return {};
    }
    if (me + s >= p) continue;  // no partner at this level: R passes up unchanged
    int kb = 0;
    Teuchos::receive(comm_, me + s, 1, &kb);
    std::vector<double> below(static_cast<size_t>(kb) * n_);
    if (kb > 0) Teuchos::receive(comm_, me + s, kb * n_, below.data());
    if (k == n_) {  // this rank's R is a full triangle: the structured QR (TriangleStackQr)
      levels_.push_back(Level{me + s, k, TriangleStackQr(n_, std::move(R), kb, std::move(below))});
    } else {  // a trapezoid on top: GEQRF of the dense stack [R; R_below], (k + kb) x n column-major
      std::vector<double> stack(static_cast<size_t>(k + kb) * n_);
      for (int j = 0; j < n_; ++j) {
        std::copy_n(R.begin() + static_cast<size_t>(k) * j, k, stack.begin() + static_cast<size_t>(k + kb) * j);
        std::copy_n(below.begin() + static_cast<size_t>(kb) * j, kb, stack.begin() + k + static_cast<size_t>(k + kb) * j);
      }
      levels_.push_back(Level{me + s, k, HouseholderQr(k + kb, n_, std::move(stack))});
    }
    std::visit([&](const auto& qr) { R = qr.r(), k = qr.k(); }, levels_.back().qr);
  }
  *rootRows = k;
  return R;
}

std::vector<double> TreeTsqr::applyQ(std::vector<double> C, int cols) const {
  if (parent_ >= 0) {
    C.assign(static_cast<size_t>(sent_) * cols, 0.0);
    if (sent_ * cols > 0) Teuchos::receive(comm_, parent_, sent_ * cols, C.data());
  }
  for (auto level = levels_.rbegin(); level != levels_.rend(); ++level) {
    const int m = std::visit([](const auto& qr) { return qr.rows(); }, level->qr);
    // the stack's rows: mine on top, the partner's below
    const std::vector<double> full = std::visit([&](const auto& qr) { return qr.applyQ(C, cols); }, level->qr);
    const std::vector<double> theirs = rowBlock(full, m, cols, level->mine, m);
    if (!theirs.empty()) Teuchos::send(comm_, static_cast<int>(theirs.size()), theirs.data(), level->partner);
    C = rowBlock(full, m, cols, 0, level->mine);
  }
  return C;
}

}  // namespace gphr
