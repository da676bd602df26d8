#include "gphr/core/LocalScatter.hpp"

#include "gphr/core/Error.hpp"

namespace gphr {

LocalScatter::LocalScatter(const CrsGraph& graph, const std::vector<GO>& rows, const std::vector<GO>& cols)
    : graph_(&graph), offsets_(rows.size(), -1), rows_(rows), cols_(cols) {
  GPHR_REQUIRE(graph.isFillComplete(), InputError, "LocalScatter: the graph must be fill complete");
  const auto lg = graph.getLocalGraphHost();
  const auto& rowMap = *graph.getRowMap();
  const auto& colMap = *graph.getColMap();
  for (size_t e = 0; e < rows.size(); ++e) {
    const LO lr = rowMap.getLocalElement(rows[e]);
    if (lr == Teuchos::OrdinalTraits<LO>::invalid()) continue;
    const LO lc = colMap.getLocalElement(cols[e]);
    for (size_t k = lg.row_map(lr); k < lg.row_map(lr + 1); ++k)
      if (lg.entries(k) == lc) offsets_[e] = static_cast<long>(k);
    GPHR_REQUIRE(offsets_[e] >= 0, InputError, "LocalScatter: entry (", rows[e], ", ", cols[e],
                 ") is not in the graph");
  }
}

void LocalScatter::add(CrsMatrix& target, const Scalar* v) const {
  const auto vals = target.getLocalMatrixHost().values;
  for (size_t e = 0; e < offsets_.size(); ++e) {
    if (offsets_[e] >= 0) {
      vals(offsets_[e]) += v[e];
    } else {
      target.sumIntoGlobalValues(rows_[e], Teuchos::tuple<GO>(cols_[e]), Teuchos::tuple<Scalar>(v[e]));
    }
  }
}

}  // namespace gphr
