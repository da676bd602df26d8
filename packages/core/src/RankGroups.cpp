#include "gphr/core/RankGroups.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>
#include <algorithm>
#include <stdexcept>

#include "gphr/core/Error.hpp"

namespace gphr {

RankGroups::RankGroups(RCP<const Comm> world, int size) : world_(std::move(world)), size_(size) {
  const int p = world_->getSize();
  GPHR_REQUIRE(size >= 1 && size <= p, InputError, "rank group size ", size, "; allowed: 1 .. ", p,
               " (the ranks there are)");
  count_ = p / size;
  group_ = std::min(world_->getRank() / size, count_ - 1);
  sub_ = world_->split(group_, world_->getRank());
}

// The rows this rank holds of groupMap, as a map of the world communicator: every global id is
// then held once in each group (a target of an Import, a source of an Export, need not be one-to-one).
RCP<const Map> RankGroups::groupRowsOnWorld(const Map& groupMap) const {
  const auto invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  return rcp(new Map(invalid, groupMap.getNodeElementList(), groupMap.getIndexBase(), world_));
}

namespace {
// dst's local rows = src's local rows (two MultiVectors over the same local ids on different maps).
void copyLocal(const MultiVector& src, MultiVector& dst) {
  auto s = src.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto d = dst.getLocalViewHost(Tpetra::Access::OverwriteAll);
  Kokkos::deep_copy(d, s);
}
}  // namespace

RCP<MultiVector> RankGroups::toGroup(const MultiVector& X, const RCP<const Map>& groupMap) const {
  const RCP<const Map> target = groupRowsOnWorld(*groupMap);
  MultiVector onWorld(target, X.getNumVectors());
  onWorld.doImport(X, Import(X.getMap(), target), Tpetra::INSERT);
  auto out = rcp(new MultiVector(groupMap, X.getNumVectors()));
  copyLocal(onWorld, *out);
  return out;
}

RCP<const Export> RankGroups::fromGroup(int owner, const Map& groupMap, const RCP<const Map>& worldMap) const {
  GPHR_REQUIRE(owner >= 0 && owner < count_, InputError, "rank group ", owner, "; allowed: 0 .. ", count_ - 1);
  const auto invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  const Teuchos::ArrayView<const GO> none;
  const RCP<const Map> source =
      rcp(new Map(invalid, group_ == owner ? groupMap.getNodeElementList() : none, groupMap.getIndexBase(), world_));
  return rcp(new Export(source, worldMap));
}

RCP<MultiVector> RankGroups::toWorld(const MultiVector* Xg, const Export& move, size_t columns) const {
  const RCP<const Map> source = move.getSourceMap();
  GPHR_REQUIRE(!Xg || (Xg->getNumVectors() == columns && Xg->getLocalLength() == source->getNodeNumElements()),
               InputError, "RankGroups::toWorld: a MultiVector of ", Xg ? Xg->getNumVectors() : 0, " columns and ",
               Xg ? Xg->getLocalLength() : 0, " local rows; allowed: ", columns, " columns and the ",
               source->getNodeNumElements(), " rows of the sending group's map");
  MultiVector onWorld(source, columns);
  if (Xg && source->getNodeNumElements() > 0) copyLocal(*Xg, onWorld);
  auto out = rcp(new MultiVector(move.getTargetMap(), columns));
  out->doExport(onWorld, move, Tpetra::INSERT);
  return out;
}

void agreeOnFailure(const Comm& world, const std::string& failure, FailureKind kind) {
  const int mine = failure.empty() ? world.getSize() : world.getRank();
  int from = 0;
  Teuchos::reduceAll(world, Teuchos::REDUCE_MIN, mine, Teuchos::outArg(from));
  if (from == world.getSize()) return;
  long head[2] = {static_cast<long>(failure.size()), static_cast<long>(kind)};  // the failing rank's
  Teuchos::broadcast(world, from, 2, head);
  std::string text = world.getRank() == from ? failure : std::string(static_cast<size_t>(head[0]), ' ');
  if (head[0] > 0) Teuchos::broadcast(world, from, static_cast<int>(head[0]), &text[0]);
  switch (static_cast<FailureKind>(head[1])) {
    case FailureKind::Input: throw InputError(text);
    case FailureKind::Internal: throw std::runtime_error(text);
    default: throw SolverError(text);
  }
}

}  // namespace gphr
