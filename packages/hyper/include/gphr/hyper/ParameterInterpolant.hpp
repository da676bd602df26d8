#pragma once
/// @file
/// Tensor-product polynomial interpolation over the parameter box at Chebyshev-Lobatto nodes
/// (barycentric form, Berrut & Trefethen, SIAM Review 46, 2004): the n-independent route by which
/// a reduced-model query rebuilds what its parameters change in L_r, f_r, c and the reference rows
/// of the sample mesh. Offline the exact values are computed at the nodes (an O(n k) projection
/// each); online a query combines the node values with the barycentric weights at its parameter,
/// O(nodes x values) work, nothing of size n. At a node the stored values are returned exactly, and
/// a function polynomial of degree < nodes in each parameter (an affine eps or gamma) is reproduced
/// to round-off; a smooth one (the SWE's Gaussian width beta) converges geometrically in the nodes.
#include <string>
#include <utility>
#include <vector>

namespace gphr {

/// Tensor-product polynomial interpolation over the parameter box at Chebyshev-Lobatto nodes.
class ParameterInterpolant {
 public:
  ParameterInterpolant() = default;  ///< An interpolant of no values.
  /// nodesPerParameter[p] >= 2 Chebyshev-Lobatto nodes on [lower_p, upper_p]; valuesPerNode values
  /// at each node (set with setNodeValues). With no parameter it holds one node: a constant.
  ParameterInterpolant(std::vector<std::pair<double, double>> box, std::vector<int> nodesPerParameter,
                       size_t valuesPerNode);

  size_t numParameters() const { return box_.size(); }  ///< Number of parameters.
  size_t numNodes() const;  ///< Number of nodes (the product of nodesPerParameter()).
  size_t valuesPerNode() const { return valuesPerNode_; }  ///< Values interpolated (per node).
  /// The parameter box, [lower, upper] per parameter.
  const std::vector<std::pair<double, double>>& box() const { return box_; }
  const std::vector<int>& nodesPerParameter() const { return counts_; }  ///< Chebyshev-Lobatto nodes per parameter.
  /// The parameter of node j (nodes ordered row-major: the last parameter varies fastest).
  std::vector<double> node(size_t j) const;
  void setNodeValues(size_t j, const std::vector<double>& values);  ///< Sets the values at node j.
  /// All node values, numNodes() x valuesPerNode() row-major (what the file stores), and back.
  const std::vector<double>& values() const { return values_; }
  void setValues(std::vector<double> values);  ///< Sets all node values (numNodes() x valuesPerNode(), row-major).

  /// The interpolant at mu (inside the box or, extrapolating, outside it). InputError if mu has the
  /// wrong number of entries or a non-finite one.
  std::vector<double> evaluate(const std::vector<double>& mu) const;
  /// Points between the nodes (the tensor grid of the midpoints of consecutive nodes, at most
  /// maxPoints of them, evenly strided): where build-time checks measure the interpolation error.
  std::vector<std::vector<double>> checkPoints(size_t maxPoints) const;

 private:
  double nodeCoordinate(size_t p, int i) const;
  /// Lagrange basis values l_i(x) of parameter p at x (barycentric formula; exact at a node).
  std::vector<double> lagrange(size_t p, double x) const;
  std::vector<std::pair<double, double>> box_;
  std::vector<int> counts_;
  size_t valuesPerNode_ = 0;
  std::vector<double> values_;
};

}  // namespace gphr
