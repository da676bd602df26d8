// The online error indicator of a query (ErrorIndicator.hpp, doc/error-estimate.md).
#include "gphr/hyper/ErrorIndicator.hpp"

#include <Teuchos_BLAS.hpp>

#include <algorithm>
#include <map>
#include <cmath>
#include <limits>

#include "gphr/core/Error.hpp"
#include "gphr/core/ReplicatedGather.hpp"
#include "gphr/hyper/SampleMesh.hpp"

namespace gphr {

std::vector<GO> indicatorDofs(GO n, int dofs) {
  GPHR_REQUIRE(n >= 1 && dofs >= 0, InputError, "error indicator: ", dofs, " sampled degrees of freedom of n = ", n,
               "; allowed: n >= 1, dofs >= 0");
  std::vector<GO> out;
  const GO count = std::min<GO>(n, dofs);
  // (i + 1/2) n / count in integers: distinct and ascending since n / count >= 1.
  for (GO i = 0; i < count; ++i) out.push_back((2 * i + 1) * n / (2 * count));
  return out;
}

IndicatorRows indicatorRows(const HamiltonianSystem& system, const MultiVector& A, int dofs) {
  IndicatorRows out;
  const GO n = system.space().n();
  for (GO i : indicatorDofs(n, dofs)) out.entries.push_back(i);
  const size_t h = out.entries.size();
  for (size_t i = 0; i < h; ++i) out.entries.push_back(n + out.entries[i]);
  if (out.entries.empty()) return out;
  out.basisRows = gatherRows(A, out.entries);
  const NonlinearTerm& term = system.nonlinearTerm();
  const auto rows = rowsTouching(term, out.entries);
  if (!rows.empty()) {  // a Q no term reaches (a linear H near Q) needs no sample of G
    out.terms = gatherRowSample(system, A, rows, gatherWeights(term, rows));
    out.terms.reference.clear();  // parameter-dependent: from the interpolant per query
  }
  out.terms.reducedDim = static_cast<int>(A.getNumVectors());
  return out;
}

IndicatorLinearRows indicatorLinearRows(const HamiltonianSystem& system, const MultiVector& A,
                                        const std::vector<GO>& entries) {
  MultiVector LA(system.map(), A.getNumVectors());
  system.linearPart().apply(A, LA);
  return IndicatorLinearRows{gatherRows(LA, entries), gatherRows(system.linearForce(), entries)};
}

double IndicatorCalibration::estimate(double eta) const {
  if (!calibrated() || !std::isfinite(eta) || eta < 0.0) return std::numeric_limits<double>::quiet_NaN();
  return scale * std::pow(eta, exponent);
}

IndicatorCalibration fitIndicatorCalibration(const std::vector<double>& eta, const std::vector<double>& error) {
  GPHR_REQUIRE(eta.size() == error.size(), InputError, "indicator calibration: ", eta.size(), " indicators and ",
               error.size(), " errors");
  std::vector<double> x, y;  // log eta, log E
  for (size_t i = 0; i < eta.size(); ++i)
    if (std::isfinite(eta[i]) && std::isfinite(error[i]) && eta[i] > 0.0 && error[i] > 0.0)
      x.push_back(std::log(eta[i])), y.push_back(std::log(error[i]));
  IndicatorCalibration c;
  c.points = static_cast<int>(x.size());
  if (x.empty()) return c;
  const double N = static_cast<double>(x.size());
  double mx = 0.0, my = 0.0;
  for (size_t i = 0; i < x.size(); ++i) mx += x[i] / N, my += y[i] / N;
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  // A 2-parameter least-squares line in closed form (no LAPACK call needed for a 2 x 2 system).
  if (x.size() >= 3 && *hi - *lo >= std::log(2.0)) {
    double sxy = 0.0, sxx = 0.0;
    for (size_t i = 0; i < x.size(); ++i) sxy += (x[i] - mx) * (y[i] - my), sxx += (x[i] - mx) * (x[i] - mx);
    c.exponent = std::min(2.0, std::max(0.5, sxy / sxx));
  }
  c.scale = std::exp(my - c.exponent * mx);
  for (size_t i = 0; i < x.size(); ++i) {
    const double ratio = std::exp(std::log(c.scale) + c.exponent * x[i] - y[i]);
    c.worstFactor = std::max(c.worstFactor, std::max(ratio, 1.0 / ratio));
  }
  return c;
}

ResidualIndicator::ResidualIndicator(RCP<const RowEvaluator> kernel, const IndicatorRows& rows,
                                     const std::vector<double>& reference, IndicatorLinearRows linear,
                                     QuadratureRule rule)
    : linear_(std::move(linear)), rule_(std::move(rule)) {
  const size_t s = rows.entries.size(), M = rows.terms.stencil.gids.size();
  r_ = rows.terms.reducedDim;
  GPHR_REQUIRE(s > 0 && s % 2 == 0 && reference.size() == s + M && rows.basisRows.size() == s * r_ &&
                   linear_.LA.size() == s * r_ && linear_.f.size() == s,
               InputError, "error indicator: ", s, " entries, ", reference.size(), " reference values (allowed: ",
               s + M, "), ", rows.basisRows.size(), " basis-row and ", linear_.LA.size(), " L A values (allowed: ",
               s * r_, " each), ", linear_.f.size(), " force values");
  // The distinct entries U: Q's, then those of the terms' stencils not in Q (a stencil entry is
  // under up to 5 rows of a 5-point stencil); each lifted once per step (yU_ + AU_ z).
  std::map<GO, int> distinct;
  const auto add = [&](GO gid, double y0, const double* Arow) {
    const auto [it, fresh] = distinct.emplace(gid, static_cast<int>(yU_.size()));
    if (fresh) yU_.push_back(y0), AU_.insert(AU_.end(), Arow, Arow + r_);
    return it->second;
  };
  for (size_t i = 0; i < s; ++i) qU_.push_back(add(rows.entries[i], reference[i], rows.basisRows.data() + i * r_));
  const RowSample& t = rows.terms;
  if (!t.rows.empty()) {
    kernel_ = std::move(kernel);
    batch_.allocate(t.rows, t.stencil.offsets, true, false);
    weight_ = t.weights;
    for (size_t j = 0; j < M; ++j) {
      entryOf_.push_back(add(t.stencil.gids[j], reference[s + j], t.basisRows.data() + j * r_));
      const auto q = std::lower_bound(rows.entries.begin(), rows.entries.end(), t.stencil.gids[j]);
      slot_.push_back(q != rows.entries.end() && *q == t.stencil.gids[j] ? static_cast<int>(q - rows.entries.begin()) : -1);
    }
    for (LO i = 0; i < t.stencil.numRows(); ++i)
      for (size_t j = t.stencil.offsets[i]; j < t.stencil.offsets[i + 1]; ++j) rowOf_.push_back(i);
  }
  vU0_.assign(yU_.size(), 0.0), vU1_.assign(yU_.size(), 0.0), vq_.assign(yU_.size(), 0.0);
  gN_.assign(s, 0.0), e_.assign(s, 0.0), gbar_.assign(s, 0.0), R_.assign(s, 0.0);
  zbar_.size(r_);
}

void ResidualIndicator::liftU(const DenseVector& z, std::vector<double>& out) const {
  std::copy(yU_.begin(), yU_.end(), out.begin());
  // out += AU z: AU row-major nU x 2k is column-major 2k x nU, hence the transposed product.
  Teuchos::BLAS<int, double>().GEMV(Teuchos::TRANS, r_, static_cast<int>(yU_.size()), 1.0, AU_.data(), r_, z.values(), 1,
                                    1.0, out.data(), 1);
}

void ResidualIndicator::nonlinearGradientAtQ(const std::vector<double>& vU) {
  for (size_t j = 0; j < entryOf_.size(); ++j) batch_.values(j) = vU[entryOf_[j]];
  kernel_->evaluate(batch_);
  std::fill(gN_.begin(), gN_.end(), 0.0);
  for (size_t j = 0; j < slot_.size(); ++j)
    if (slot_[j] >= 0) gN_[slot_[j]] += weight_[rowOf_[j]] * batch_.grad(j);
}

void ResidualIndicator::start(const DenseVector& z0) {
  num_ = den_ = 0.0;
  std::fill(e_.begin(), e_.end(), 0.0);
  liftU(z0, vU0_);
  for (int u : qU_) den_ += vU0_[u] * vU0_[u];
  started_ = true;
}

void ResidualIndicator::step(const DenseVector& z0, const DenseVector& z1, double dt) {
  const size_t s = qU_.size(), h = s / 2;
  // The lift is affine in z: at z1 once (one product), at every quadrature node from the two
  // ends, vU0_ holding z0's lift from the previous call (start or step: the time loop passes
  // z0 = the last z1).
  liftU(z1, vU1_);
  // The linear part of gbar is L A zbar + f with zbar = sum_q w_q z_q = z0 + (sum_q w_q s_q)(z1 - z0):
  // one product for all nodes; the nonlinear part needs the kernel at each node.
  double sbar = 0.0;
  for (int q = 0; q < rule_.size(); ++q) sbar += rule_.weights[q] * rule_.nodes[q];
  for (int c = 0; c < r_; ++c) zbar_(c) = z0(c) + sbar * (z1(c) - z0(c));
  std::copy(linear_.f.begin(), linear_.f.end(), gbar_.begin());
  // gbar += LA zbar: LA row-major s x 2k, as AU above.
  Teuchos::BLAS<int, double>().GEMV(Teuchos::TRANS, r_, static_cast<int>(s), 1.0, linear_.LA.data(), r_,
                                    zbar_.values(), 1, 1.0, gbar_.data(), 1);
  for (int q = 0; kernel_ && q < rule_.size(); ++q) {
    const double sq = rule_.nodes[q];
    for (size_t u = 0; u < vq_.size(); ++u) vq_[u] = vU0_[u] + sq * (vU1_[u] - vU0_[u]);
    nonlinearGradientAtQ(vq_);
    for (size_t i = 0; i < s; ++i) gbar_[i] += rule_.weights[q] * gN_[i];
  }
  // R = y1_Q - y0_Q - dt (J gbar)_Q with (J g)_{q_i} = g_{p_i}, (J g)_{p_i} = -g_{q_i}.
  // e_j = e_{j-1} - R_j: the error equation K e_j = (2I - K) e_{j-1} - R_j with K = I.
  double e2 = 0.0, y2 = 0.0;
  for (size_t i = 0; i < s; ++i) {
    const double Jg = i < h ? gbar_[i + h] : -gbar_[i - h], y1 = vU1_[qU_[i]];
    R_[i] = y1 - vU0_[qU_[i]] - dt * Jg;
    e_[i] -= R_[i];
    e2 += e_[i] * e_[i];
    y2 += y1 * y1;
  }
  vU0_.swap(vU1_);
  num_ += e2;
  den_ += y2;
}

double ResidualIndicator::value() const {
  if (!started_ || !(den_ > 0.0) || !std::isfinite(num_)) return std::numeric_limits<double>::quiet_NaN();
  return std::sqrt(num_ / den_);
}

}  // namespace gphr
