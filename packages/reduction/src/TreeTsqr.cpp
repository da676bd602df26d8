#include "gphr/reduction/TreeTsqr.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_LAPACK.hpp>

#include <algorithm>

#include "gphr/core/Error.hpp"

namespace gphr {

HouseholderQr::HouseholderQr(int m, int n, std::vector<double> a) : m_(m), n_(n), a_(std::move(a)) {
  tau_.assign(std::max(k(), 1), 0.0);
  if (k() == 0) return;
  Teuchos::LAPACK<int, double> lapack;
  std::vector<double> work(1);
  int info = 0;
  lapack.GEQRF(m_, n_, a_.data(), m_, tau_.data(), work.data(), -1, &info);
  work.resize(std::max(1, static_cast<int>(work[0])));
  lapack.GEQRF(m_, n_, a_.data(), m_, tau_.data(), work.data(), static_cast<int>(work.size()), &info);
  GPHR_REQUIRE(info == 0, SolverError, "Householder QR: LAPACK GEQRF of ", m_, " x ", n_, " failed (info = ", info, ")");
}

std::vector<double> HouseholderQr::r() const {
  const int kk = k();
  std::vector<double> R(static_cast<size_t>(kk) * n_, 0.0);
  for (int j = 0; j < n_; ++j)
    for (int i = 0; i < std::min(kk, j + 1); ++i) R[i + static_cast<size_t>(kk) * j] = a_[i + static_cast<size_t>(m_) * j];
  return R;
}

std::vector<double> HouseholderQr::applyQ(const std::vector<double>& C, int cols) const {
  const int kk = k();
  std::vector<double> out(static_cast<size_t>(m_) * cols, 0.0);
  for (int j = 0; j < cols; ++j)
    std::copy_n(C.begin() + static_cast<size_t>(kk) * j, kk, out.begin() + static_cast<size_t>(m_) * j);
  if (kk == 0 || cols == 0) return out;
  Teuchos::LAPACK<int, double> lapack;
  std::vector<double> work(1);
  int info = 0;
  // ORMQR only reads the reflectors; Teuchos::LAPACK (Trilinos 13.2) declares them non-const.
  double* a = const_cast<double*>(a_.data());
  double* tau = const_cast<double*>(tau_.data());
  lapack.ORMQR('L', 'N', m_, cols, kk, a, m_, tau, out.data(), m_, work.data(), -1, &info);
  work.resize(std::max(1, static_cast<int>(work[0])));
  lapack.ORMQR('L', 'N', m_, cols, kk, a, m_, tau, out.data(), m_, work.data(),
               static_cast<int>(work.size()), &info);
  GPHR_REQUIRE(info == 0, SolverError, "Householder QR: LAPACK ORMQR on ", m_, " x ", cols, " failed (info = ", info, ")");
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
    // The stack [R; R_below], (k + kb) x n column-major.
    std::vector<double> stack(static_cast<size_t>(k + kb) * n_);
    for (int j = 0; j < n_; ++j) {
      std::copy_n(R.begin() + static_cast<size_t>(k) * j, k, stack.begin() + static_cast<size_t>(k + kb) * j);
      std::copy_n(below.begin() + static_cast<size_t>(kb) * j, kb, stack.begin() + k + static_cast<size_t>(k + kb) * j);
    }
    levels_.push_back(Level{me + s, k, HouseholderQr(k + kb, n_, std::move(stack))});
    R = levels_.back().qr.r();
    k = levels_.back().qr.k();
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
    const int m = level->qr.rows();
    const std::vector<double> full = level->qr.applyQ(C, cols);  // the stack's rows: mine on top, the partner's below
    const std::vector<double> theirs = rowBlock(full, m, cols, level->mine, m);
    if (!theirs.empty()) Teuchos::send(comm_, static_cast<int>(theirs.size()), theirs.data(), level->partner);
    C = rowBlock(full, m, cols, 0, level->mine);
  }
  return C;
}

}  // namespace gphr
