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

NonlinearTerm::NonlinearTerm(RCP<const Map> rowMap, RCP<const Map> stateMap, Stencil stencil,
                             RCP<const Vector> weights, int degree)
    : RowEvaluator(degree), rowMap_(rowMap), stateMap_(stateMap), stencil_(std::move(stencil)), weights_(weights) {
  const LO nr = static_cast<LO>(rowMap_->getNodeNumElements());
  GPHR_REQUIRE(stencil_.numRows() == nr, InputError, "nonlinear term: the stencil lists ",
               stencil_.numRows(), " rows but this rank owns ", nr, " rows of G");
  GPHR_REQUIRE(weights_->getMap()->isSameAs(*rowMap_), InputError,
               "nonlinear term: the weights v must live on the row map of G");
  std::vector<size_t> counts(nr);
  for (LO r = 0; r < nr; ++r) counts[r] = stencil_.size(r);
  auto graph = rcp(new CrsGraph(rowMap_, Teuchos::ArrayView<const size_t>(counts.data(), nr)));
  for (LO r = 0; r < nr; ++r) {
    const LO s = stencil_.size(r);
    maxStencil_ = std::max<int>(maxStencil_, s);
    std::vector<GO> cols(stencil_.gids.begin() + stencil_.offsets[r],
                         stencil_.gids.begin() + stencil_.offsets[r + 1]);
    std::sort(cols.begin(), cols.end());
    GPHR_REQUIRE(std::adjacent_find(cols.begin(), cols.end()) == cols.end(), InputError,
                 "nonlinear term: row ", rowMap_->getGlobalElement(r),
                 " lists a state entry twice in its stencil (is the grid too small?)");
    graph->insertGlobalIndices(rowMap_->getGlobalElement(r),
                               Teuchos::ArrayView<const GO>(cols.data(), cols.size()));
  }
  graph->fillComplete(stateMap_, rowMap_);
  jacobianGraph_ = graph;
}

}  // namespace gphr
