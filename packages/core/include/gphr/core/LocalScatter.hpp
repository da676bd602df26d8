#pragma once
/// @file
/// Positions of (global row, global column) pairs in the values array of a matrix on a
/// fill-complete static graph, computed once per graph. Assemblies then add into one host view
/// of the values instead of calling sumIntoGlobalValues per row: that call's view handling
/// (Kokkos reference counting) was a third of the full model's time stepping (perf, SWE 50x50).
/// Pairs in rows owned by another rank keep the sumIntoGlobalValues path (summed at fillComplete).
#include <vector>

#include "gphr/core/Types.hpp"

namespace gphr {

/// Positions of (global row, global column) pairs in a matrix's values array, computed once per graph.
class LocalScatter {
 public:
  LocalScatter() = default;  ///< An empty scatter (built for no graph).
  /// rows[e], cols[e]: global ids of entry e; the graph must be fill complete and hold every
  /// owned pair.
  LocalScatter(const CrsGraph& graph, const std::vector<GO>& rows, const std::vector<GO>& cols);
  /// Whether this scatter was built for `graph`.
  bool builtFor(const CrsGraph* graph) const { return graph_ == graph; }
  size_t size() const { return offsets_.size(); }  ///< Number of entries.

  /// values[offset(e)] += v[e] for owned entries; sumIntoGlobalValues for the others.
  /// target must be fill-active (resumeFill) on the graph this scatter was built for.
  void add(CrsMatrix& target, const Scalar* v) const;

 private:
  const CrsGraph* graph_ = nullptr;
  std::vector<long> offsets_;  ///< -1: row owned elsewhere
  std::vector<GO> rows_, cols_;
};

}  // namespace gphr
