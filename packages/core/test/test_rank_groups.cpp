// RankGroups: the split of the world into groups and the two moves between a world MultiVector
// and a group's copy. Every entry is a small integer (exact in double), and both moves copy: they
// are checked for exact equality.
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>

#include <stdexcept>

#include "gphr/core/Error.hpp"
#include "gphr/core/RankGroups.hpp"

namespace gphr {
namespace {

constexpr GO kRows = 11;  // not a multiple of 2 or 3: uneven rows per rank in the world and in groups
double entry(GO i, size_t j) { return static_cast<double>(i + 100 * static_cast<GO>(j) + 1); }

TEST(RankGroups, SplitIntoConsecutiveRanks) {
  auto world = Tpetra::getDefaultComm();
  const int p = world->getSize();
  for (int size = 1; size <= p; ++size) {
    const RankGroups g(world, size);
    EXPECT_EQ(g.count(), p / size);
    EXPECT_EQ(g.group(), std::min(world->getRank() / size, p / size - 1));
    EXPECT_EQ(g.sub()->getSize(), g.group() == g.count() - 1 ? p - size * (g.count() - 1) : size);
  }
  EXPECT_THROW(RankGroups(world, 0), InputError);
  EXPECT_THROW(RankGroups(world, p + 1), InputError);
}

TEST(RankGroups, EveryGroupGetsAllOfAWorldMultiVector) {
  auto world = Tpetra::getDefaultComm();
  for (int size = 1; size <= world->getSize(); ++size) {
    const RankGroups g(world, size);
    auto worldMap = rcp(new Map(kRows, 0, world));
    MultiVector X(worldMap, 3);
    for (LO l = 0; l < static_cast<LO>(worldMap->getNodeNumElements()); ++l)
      for (size_t j = 0; j < 3; ++j) X.replaceLocalValue(l, j, entry(worldMap->getGlobalElement(l), j));
    auto groupMap = rcp(new Map(kRows, 0, g.sub()));
    const RCP<MultiVector> Xg = g.toGroup(X, groupMap);
    ASSERT_TRUE(Xg->getMap()->isSameAs(*groupMap));
    auto v = Xg->getLocalViewHost(Tpetra::Access::ReadOnly);
    for (LO l = 0; l < static_cast<LO>(groupMap->getNodeNumElements()); ++l)
      for (size_t j = 0; j < 3; ++j) EXPECT_EQ(v(l, j), entry(groupMap->getGlobalElement(l), j)) << "size " << size;
  }
}

TEST(RankGroups, ToWorldMovesOneGroupsMultiVector) {
  auto world = Tpetra::getDefaultComm();
  for (int size = 1; size <= world->getSize(); ++size) {
    const RankGroups g(world, size);
    auto groupMap = rcp(new Map(kRows, 0, g.sub()));
    auto worldMap = rcp(new Map(kRows, 0, world));
    for (int owner = 0; owner < g.count(); ++owner) {
      const size_t cols = 2 + static_cast<size_t>(owner);
      MultiVector Xg(groupMap, cols);  // the owner's numbers; every other group's would be -1
      for (LO l = 0; l < static_cast<LO>(groupMap->getNodeNumElements()); ++l)
        for (size_t j = 0; j < cols; ++j)
          Xg.replaceLocalValue(l, j, g.group() == owner ? entry(groupMap->getGlobalElement(l), j) : -1.0);
      const RCP<const Export> move = g.fromGroup(owner, *groupMap, worldMap);
      const RCP<MultiVector> X = g.toWorld(g.group() == owner ? &Xg : nullptr, *move, cols);
      ASSERT_TRUE(X->getMap()->isSameAs(*worldMap));
      ASSERT_EQ(X->getNumVectors(), cols);
      auto v = X->getLocalViewHost(Tpetra::Access::ReadOnly);
      for (LO l = 0; l < static_cast<LO>(worldMap->getNodeNumElements()); ++l)
        for (size_t j = 0; j < cols; ++j)
          EXPECT_EQ(v(l, j), entry(worldMap->getGlobalElement(l), j)) << "size " << size << ", owner " << owner;
    }
    EXPECT_THROW(g.fromGroup(g.count(), *groupMap, worldMap), InputError);
  }
}

// Every rank throws the failure of the lowest failing rank, as the kind that rank gave: a group
// that failed ends the work on all ranks with one message, and an input error stays one (exit 2).
TEST(RankGroups, AgreeOnFailureThrowsTheLowestFailingRanksErrorEverywhere) {
  auto world = Tpetra::getDefaultComm();
  const int p = world->getSize(), me = world->getRank();
  EXPECT_NO_THROW(agreeOnFailure(*world, ""));
  const int lowest = p > 1 ? 1 : 0;  // ranks from 1 on fail (rank 0 too on one rank)
  const std::string mine = me >= lowest ? "rank " + std::to_string(me) + " failed" : "";
  const std::string expected = "rank " + std::to_string(lowest) + " failed";
  // each failing rank names its own kind; the lowest one's decides: Input, Solver, Internal in turn
  for (FailureKind kind : {FailureKind::Input, FailureKind::Solver, FailureKind::Internal}) {
    const FailureKind given = me == lowest ? kind : FailureKind::Solver;
    try {
      agreeOnFailure(*world, mine, given);
      ADD_FAILURE() << "no exception";
    } catch (const InputError& e) {
      EXPECT_EQ(kind, FailureKind::Input);
      EXPECT_EQ(std::string(e.what()), expected);
    } catch (const SolverError& e) {
      EXPECT_EQ(kind, FailureKind::Solver);
      EXPECT_EQ(std::string(e.what()), expected);
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(kind, FailureKind::Internal);
      EXPECT_EQ(std::string(e.what()), expected);
    }
  }
}

TEST(RankGroups, FailureOfNamesWhatWorkThrew) {
  EXPECT_EQ(failureOf("item 2", "it failed: ", [] {}).text, "");
  const GroupFailure solver = failureOf("item 2", "it failed: ", [] { throw SolverError("no convergence"); });
  EXPECT_EQ(solver.text, "item 2: it failed: no convergence");
  EXPECT_EQ(solver.kind, FailureKind::Solver);
  const GroupFailure input = failureOf("item 2", "it failed: ", [] { throw InputError("eps = -1"); });
  EXPECT_EQ(input.text, "item 2: eps = -1");
  EXPECT_EQ(input.kind, FailureKind::Input);
  const GroupFailure internal = failureOf("item 2", "it failed: ", [] { throw std::logic_error("bad state"); });
  EXPECT_EQ(internal.text, "item 2: bad state");
  EXPECT_EQ(internal.kind, FailureKind::Internal);
}

}  // namespace
}  // namespace gphr
