#include "gphr/hyper/ParameterInterpolant.hpp"

#include <cmath>

#include "gphr/core/Error.hpp"

namespace gphr {

ParameterInterpolant::ParameterInterpolant(std::vector<std::pair<double, double>> box,
                                           std::vector<int> nodesPerParameter, size_t valuesPerNode)
    : box_(std::move(box)), counts_(std::move(nodesPerParameter)), valuesPerNode_(valuesPerNode) {
  GPHR_REQUIRE(box_.size() == counts_.size(), InputError, "parameter interpolant: ", box_.size(),
               " parameters but ", counts_.size(), " node counts");
  for (size_t p = 0; p < box_.size(); ++p) {
    GPHR_REQUIRE(counts_[p] >= 2 && counts_[p] <= 64, InputError, "parameter interpolant: ", counts_[p],
                 " nodes for parameter ", p, "; allowed: 2 to 64");
    GPHR_REQUIRE(box_[p].first < box_[p].second, InputError, "parameter interpolant: interval [", box_[p].first,
                 ", ", box_[p].second, "] of parameter ", p, " is empty");
  }
  values_.assign(numNodes() * valuesPerNode_, 0.0);
}

size_t ParameterInterpolant::numNodes() const {
  size_t n = 1;  // no parameter: one node, the constant
  for (int c : counts_) n *= static_cast<size_t>(c);
  return n;
}

double ParameterInterpolant::nodeCoordinate(size_t p, int i) const {
  // x_i = mid + half cos(pi i / (N - 1)): descending from the upper bound; the end nodes are
  // the bounds themselves (set exactly, not through cos, so a query at a bound hits the node).
  const int N = counts_[p];
  if (i == 0) return box_[p].second;
  if (i == N - 1) return box_[p].first;
  const double mid = 0.5 * (box_[p].first + box_[p].second), half = 0.5 * (box_[p].second - box_[p].first);
  return mid + half * std::cos(M_PI * i / (N - 1));
}

std::vector<double> ParameterInterpolant::node(size_t j) const {
  std::vector<double> mu(box_.size());
  for (size_t p = box_.size(); p-- > 0;) {
    mu[p] = nodeCoordinate(p, static_cast<int>(j % counts_[p]));
    j /= counts_[p];
  }
  return mu;
}

void ParameterInterpolant::setNodeValues(size_t j, const std::vector<double>& values) {
  GPHR_REQUIRE(j < numNodes() && values.size() == valuesPerNode_, InputError, "parameter interpolant: node ", j,
               " of ", numNodes(), " given ", values.size(), " values (expected ", valuesPerNode_, ")");
  std::copy(values.begin(), values.end(), values_.begin() + j * valuesPerNode_);
}

void ParameterInterpolant::setValues(std::vector<double> values) {
  GPHR_REQUIRE(values.size() == numNodes() * valuesPerNode_, InputError, "parameter interpolant: ", values.size(),
               " values for ", numNodes(), " nodes of ", valuesPerNode_);
  values_ = std::move(values);
}

// Barycentric weights of the Chebyshev-Lobatto points: (-1)^i, halved at both ends.
std::vector<double> ParameterInterpolant::lagrange(size_t p, double x) const {
  const int N = counts_[p];
  std::vector<double> l(N, 0.0);
  double sum = 0.0;
  for (int i = 0; i < N; ++i) {
    const double xi = nodeCoordinate(p, i);
    if (x == xi) {  // at a node: the node's value, exactly
      std::fill(l.begin(), l.end(), 0.0);
      l[i] = 1.0;
      return l;
    }
    const double w = ((i % 2) ? -1.0 : 1.0) * ((i == 0 || i == N - 1) ? 0.5 : 1.0);
    l[i] = w / (x - xi);
    sum += l[i];
  }
  for (double& v : l) v /= sum;
  return l;
}

std::vector<double> ParameterInterpolant::evaluate(const std::vector<double>& mu) const {
  GPHR_REQUIRE(mu.size() == box_.size(), InputError, "parameter interpolant: ", mu.size(), " parameters given, ",
               box_.size(), " expected");
  std::vector<std::vector<double>> l;
  for (size_t p = 0; p < mu.size(); ++p) {
    GPHR_REQUIRE(std::isfinite(mu[p]), InputError, "parameter ", p, " is ", mu[p], "; allowed: a finite number");
    l.push_back(lagrange(p, mu[p]));
  }
  std::vector<double> out(valuesPerNode_, 0.0);
  for (size_t j = 0, nn = numNodes(); j < nn; ++j) {
    double c = 1.0;
    for (size_t p = box_.size(), r = j; p-- > 0; r /= counts_[p]) c *= l[p][r % counts_[p]];
    if (c == 0.0) continue;
    const double* v = values_.data() + j * valuesPerNode_;
    for (size_t i = 0; i < valuesPerNode_; ++i) out[i] += c * v[i];
  }
  return out;
}

std::vector<std::vector<double>> ParameterInterpolant::checkPoints(size_t maxPoints) const {
  size_t total = 1;
  for (int c : counts_) total *= static_cast<size_t>(c - 1);
  const size_t stride = std::max<size_t>(1, (total + maxPoints - 1) / std::max<size_t>(1, maxPoints));
  std::vector<std::vector<double>> out;
  for (size_t j = 0; j < total; j += stride) {
    std::vector<double> mu(box_.size());
    for (size_t p = box_.size(), r = j; p-- > 0; r /= (counts_[p] - 1)) {
      const int i = static_cast<int>(r % (counts_[p] - 1));
      mu[p] = 0.5 * (nodeCoordinate(p, i) + nodeCoordinate(p, i + 1));
    }
    out.push_back(mu);
  }
  return out;
}

}  // namespace gphr
