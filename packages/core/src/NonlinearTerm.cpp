#include "gphr/core/NonlinearTerm.hpp"

#include <algorithm>

#include "gphr/core/Error.hpp"

namespace gphr {

void RowBatch::allocate(const std::vector<GO>& rowIds, const std::vector<size_t>& stencilOffsets,
                        bool withGradient, bool withHessian) {
  const size_t nr = rowIds.size();
  rows = Kokkos::View<GO*, Kokkos::HostSpace>("gphr::batch.rows", nr);
  offsets = OffsetView("gphr::batch.offsets", nr + 1);
  hessOffsets = OffsetView("gphr::batch.hessOffsets", nr + 1);
  for (size_t e = 0; e < nr; ++e) {
    rows(e) = rowIds[e];
    offsets(e) = stencilOffsets[e];
    const size_t s = stencilOffsets[e + 1] - stencilOffsets[e];
    hessOffsets(e + 1) = hessOffsets(e) + s * s;
  }
  offsets(nr) = stencilOffsets[nr];
  values = HostView1("gphr::batch.values", offsets(nr));
  g = HostView1("gphr::batch.g", nr);
  grad = withGradient ? HostView1("gphr::batch.grad", offsets(nr)) : HostView1();
  hess = withHessian ? HostView1("gphr::batch.hess", hessOffsets(nr)) : HostView1();
}

TermLayout::TermLayout(RCP<const Map> rows, RCP<const Map> states, Stencil st, RCP<const Vector> v)
    : rowMap(rows), stateMap(states), stencil(std::move(st)), weights(v) {
  const LO nr = static_cast<LO>(rowMap->getNodeNumElements());
  GPHR_REQUIRE(stencil.numRows() == nr, InputError, "nonlinear term: the stencil lists ", stencil.numRows(),
               " rows but this rank owns ", nr, " rows of G");
  GPHR_REQUIRE(weights->getMap()->isSameAs(*rowMap), InputError,
               "nonlinear term: the weights v must live on the row map of G");
  std::vector<size_t> counts(nr);
  for (LO r = 0; r < nr; ++r) counts[r] = stencil.size(r);
  auto graph = rcp(new CrsGraph(rowMap, Teuchos::ArrayView<const size_t>(counts.data(), nr)));
  for (LO r = 0; r < nr; ++r) {
    const LO s = stencil.size(r);
    maxStencil = std::max<int>(maxStencil, s);
    std::vector<GO> cols(stencil.gids.begin() + stencil.offsets[r], stencil.gids.begin() + stencil.offsets[r + 1]);
    std::sort(cols.begin(), cols.end());
    GPHR_REQUIRE(std::adjacent_find(cols.begin(), cols.end()) == cols.end(), InputError,
                 "nonlinear term: row ", rowMap->getGlobalElement(r),
                 " lists a state entry twice in its stencil (is the grid too small?)");
    graph->insertGlobalIndices(rowMap->getGlobalElement(r), Teuchos::ArrayView<const GO>(cols.data(), cols.size()));
  }
  graph->fillComplete(stateMap, rowMap);
  jacobianGraph = graph;
  const auto overlap = graph->getColMap();
  overlapImport = rcp(new Import(stateMap, overlap));
  stencilLids.resize(stencil.gids.size());
  for (size_t j = 0; j < stencil.gids.size(); ++j) stencilLids[j] = overlap->getLocalElement(stencil.gids[j]);
}

NonlinearTerm::NonlinearTerm(RCP<const Map> rowMap, RCP<const Map> stateMap, Stencil stencil,
                             RCP<const Vector> weights, int degree)
    : NonlinearTerm(std::make_shared<const TermLayout>(rowMap, stateMap, std::move(stencil), weights), degree) {}

NonlinearTerm::NonlinearTerm(std::shared_ptr<const TermLayout> layout, int degree)
    : RowEvaluator(degree), layout_(std::move(layout)) {
  GPHR_REQUIRE(layout_ != nullptr, InputError, "nonlinear term: no layout");
}

}  // namespace gphr
