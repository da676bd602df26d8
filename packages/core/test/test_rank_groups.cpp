// RankGroups: the split of the world into groups and the two moves between a world MultiVector
// and each group's copy. Every entry is a small integer (exact in double), so both moves are
// checked for exact equality: toGroup copies, and toWorld adds a group's numbers to zeros only.
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>

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

TEST(RankGroups, ToWorldSumsWhatEachGroupFilled) {
  auto world = Tpetra::getDefaultComm();
  for (int size = 1; size <= world->getSize(); ++size) {
    const RankGroups g(world, size);
    auto groupMap = rcp(new Map(kRows, 0, g.sub()));
    const size_t cols = static_cast<size_t>(g.count()) + 1;
    MultiVector Xg(groupMap, cols);  // column c filled by group c only; the last column by every group
    for (LO l = 0; l < static_cast<LO>(groupMap->getNodeNumElements()); ++l) {
      const GO i = groupMap->getGlobalElement(l);
      Xg.replaceLocalValue(l, g.group(), entry(i, g.group()));
      Xg.replaceLocalValue(l, cols - 1, 1.0);
    }
    auto worldMap = rcp(new Map(kRows, 0, world));
    const RCP<MultiVector> X = g.toWorld(Xg, worldMap);
    auto v = X->getLocalViewHost(Tpetra::Access::ReadOnly);
    for (LO l = 0; l < static_cast<LO>(worldMap->getNodeNumElements()); ++l) {
      const GO i = worldMap->getGlobalElement(l);
      for (size_t c = 0; c + 1 < cols; ++c) EXPECT_EQ(v(l, c), entry(i, c)) << "size " << size << ", column " << c;
      EXPECT_EQ(v(l, cols - 1), static_cast<double>(g.count())) << "size " << size;  // one per group
    }
  }
}

}  // namespace
}  // namespace gphr
