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
    : AQ_(rows.basisRows), linear_(std::move(linear)), rule_(std::move(rule)) {
  const size_t s = rows.entries.size(), M = rows.terms.stencil.gids.size();
  r_ = rows.terms.reducedDim;
  GPHR_REQUIRE(s > 0 && s % 2 == 0 && reference.size() == s + M && AQ_.size() == s * r_ &&
                   linear_.LA.size() == s * r_ && linear_.f.size() == s,
               InputError, "error indicator: ", s, " entries, ", reference.size(), " reference values (allowed: ",
               s + M, "), ", AQ_.size(), " basis-row and ", linear_.LA.size(), " L A values (allowed: ", s * r_,
               " each), ", linear_.f.size(), " force values");
  yref_.assign(reference.begin(), reference.begin() + s);
  const RowSample& t = rows.terms;
  if (!t.rows.empty()) {
    kernel_ = std::move(kernel);
    batch_.allocate(t.rows, t.stencil.offsets, true, false);
    weight_ = t.weights;
    std::map<GO, int> distinct;
    for (size_t j = 0; j < M; ++j) {
      const auto [it, fresh] = distinct.emplace(t.stencil.gids[j], static_cast<int>(yU_.size()));
      if (fresh) {
        yU_.push_back(reference[s + j]);
        AU_.insert(AU_.end(), t.basisRows.begin() + j * r_, t.basisRows.begin() + (j + 1) * r_);
      }
      entryOf_.push_back(it->second);
      const auto q = std::lower_bound(rows.entries.begin(), rows.entries.end(), t.stencil.gids[j]);
      slot_.push_back(q != rows.entries.end() && *q == t.stencil.gids[j] ? static_cast<int>(q - rows.entries.begin()) : -1);
    }
    for (LO i = 0; i < t.stencil.numRows(); ++i)
      for (size_t j = t.stencil.offsets[i]; j < t.stencil.offsets[i + 1]; ++j) rowOf_.push_back(i);
    vU_.assign(yU_.size(), 0.0);
  }
  gN_.assign(s, 0.0), e_.assign(s, 0.0), gbar_.assign(s, 0.0), R_.assign(s, 0.0), y_.assign(s, 0.0);
  zq_.size(r_);
}

void ResidualIndicator::nonlinearGradientAtQ(const DenseVector& z) {
  const int nU = static_cast<int>(yU_.size());
  std::copy(yU_.begin(), yU_.end(), vU_.begin());
  // vU += AU z: AU row-major nU x 2k is column-major 2k x nU, hence the transposed product.
  Teuchos::BLAS<int, double>().GEMV(Teuchos::TRANS, r_, nU, 1.0, AU_.data(), r_, z.values(), 1, 1.0, vU_.data(), 1);
  for (size_t j = 0; j < entryOf_.size(); ++j) batch_.values(j) = vU_[entryOf_[j]];
  kernel_->evaluate(batch_);
  std::fill(gN_.begin(), gN_.end(), 0.0);
  for (size_t j = 0; j < slot_.size(); ++j)
    if (slot_[j] >= 0) gN_[slot_[j]] += weight_[rowOf_[j]] * batch_.grad(j);
}

void ResidualIndicator::liftQ(const DenseVector& z, std::vector<double>& out) const {
  for (size_t i = 0; i < yref_.size(); ++i) {
    double v = yref_[i];
    for (int c = 0; c < r_; ++c) v += AQ_[i * r_ + c] * z(c);
    out[i] = v;
  }
}

void ResidualIndicator::start(const DenseVector& z0) {
  num_ = den_ = 0.0;
  std::fill(e_.begin(), e_.end(), 0.0);
  liftQ(z0, y_);
  for (double v : y_) den_ += v * v;
  started_ = true;
}

void ResidualIndicator::step(const DenseVector& z0, const DenseVector& z1, double dt) {
  const size_t s = yref_.size(), h = s / 2;
  // The linear part of gbar is L A zbar + f with zbar = sum_q w_q z_q = z0 + (sum_q w_q s_q)(z1 - z0):
  // one product for all nodes; the nonlinear part needs the kernel at each node.
  double sbar = 0.0;
  for (int q = 0; q < rule_.size(); ++q) sbar += rule_.weights[q] * rule_.nodes[q];
  for (int c = 0; c < r_; ++c) zq_(c) = z0(c) + sbar * (z1(c) - z0(c));
  for (size_t i = 0; i < s; ++i) {
    double g = linear_.f[i];
    for (int c = 0; c < r_; ++c) g += linear_.LA[i * r_ + c] * zq_(c);
    gbar_[i] = g;
  }
  for (int q = 0; kernel_ && q < rule_.size(); ++q) {
    for (int c = 0; c < r_; ++c) zq_(c) = z0(c) + rule_.nodes[q] * (z1(c) - z0(c));
    nonlinearGradientAtQ(zq_);
    for (size_t i = 0; i < s; ++i) gbar_[i] += rule_.weights[q] * gN_[i];
  }
  // R = y1_Q - y0_Q - dt (J gbar)_Q with (J g)_{q_i} = g_{p_i}, (J g)_{p_i} = -g_{q_i}; y_ holds
  // y0_Q from the previous call (start or step: the time loop passes z0 = the last z1).
  std::copy(y_.begin(), y_.end(), R_.begin());
  liftQ(z1, y_);
  // e_j = e_{j-1} - R_j: the error equation K e_j = (2I - K) e_{j-1} - R_j with K = I.
  double e2 = 0.0, y2 = 0.0;
  for (size_t i = 0; i < s; ++i) {
    const double Jg = i < h ? gbar_[i + h] : -gbar_[i - h];
    R_[i] = y_[i] - R_[i] - dt * Jg;
    e_[i] -= R_[i];
    e2 += e_[i] * e_[i];
    y2 += y_[i] * y_[i];
  }
  num_ += e2;
  den_ += y2;
}

double ResidualIndicator::value() const {
  if (!started_ || !(den_ > 0.0) || !std::isfinite(num_)) return std::numeric_limits<double>::quiet_NaN();
  return std::sqrt(num_ / den_);
}

}  // namespace gphr
