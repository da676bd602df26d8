// gatherRows against the entries written out by formula (every rank knows them), on 1, 2 and 3
// ranks with uneven and non-contiguous ownership: the rows come back exactly (one rank
// contributes each), in the order asked, repeats included; an id outside the map, or one that
// two ranks own, is refused on every rank, naming it.
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>
#include <cmath>

#include "gphr/core/Error.hpp"
#include "gphr/core/ReplicatedGather.hpp"

namespace gphr {
namespace {

constexpr GO kRows = 101;  // uneven rows per rank on 2 and 3 ranks
constexpr size_t kCols = 5;
double entry(GO i, size_t j) { return std::sin(0.37 * static_cast<double>(i) + 1.3 * static_cast<double>(j)); }

// Rows dealt to the ranks round-robin (row i on rank i mod p): no rank holds a contiguous block.
RCP<const Map> cyclicMap() {
  auto comm = Tpetra::getDefaultComm();
  const int p = comm->getSize(), me = comm->getRank();
  std::vector<GO> mine;
  for (GO i = me; i < kRows; i += p) mine.push_back(i);
  return rcp(new Map(kRows, mine.data(), mine.size(), 0, comm));
}

MultiVector filled(const RCP<const Map>& map) {
  MultiVector X(map, kCols);
  for (LO l = 0; l < static_cast<LO>(map->getNodeNumElements()); ++l)
    for (size_t j = 0; j < kCols; ++j) X.replaceLocalValue(l, j, entry(map->getGlobalElement(l), j));
  return X;
}

const std::vector<GO> kAsked{100, 0, 57, 3, 57, 42, 1, 99, 2};  // out of order, 57 twice

void expectRows(const std::vector<Scalar>& rows) {
  ASSERT_EQ(rows.size(), kAsked.size() * kCols);
  for (size_t i = 0; i < kAsked.size(); ++i)
    for (size_t j = 0; j < kCols; ++j) EXPECT_EQ(rows[i * kCols + j], entry(kAsked[i], j)) << kAsked[i] << ", " << j;
}

TEST(ReplicatedGather, RowsComeBackExactlyInTheOrderAsked) {
  for (const auto& map : {RCP<const Map>(rcp(new Map(kRows, 0, Tpetra::getDefaultComm()))), cyclicMap()}) {
    const MultiVector X = filled(map);
    expectRows(gatherRows(X, kAsked));
    const LocalRows local(X);
    expectRows(gatherRows(local, kAsked));
    expectRows(gatherRows(*map, local.rows, static_cast<int>(kCols), kAsked));
    EXPECT_TRUE(gatherRows(X, {}).empty());
  }
}

TEST(ReplicatedGather, AnIdOutsideTheMapIsRefusedOnEveryRank) {
  const MultiVector X = filled(cyclicMap());
  try {
    gatherRows(X, {3, kRows + 7, 5});
    FAIL() << "no error for a row outside the map";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("global id 108 is not an entry of the map"), std::string::npos) << e.what();
  }
}

// Row 0 on every rank besides the cyclic rows (an overlapping map): a gather cannot tell whose
// copy to take, and says so; on one rank the map stays one-to-one and the rows come back.
TEST(ReplicatedGather, AnIdOwnedByTwoRanksIsRefused) {
  auto comm = Tpetra::getDefaultComm();
  const int p = comm->getSize(), me = comm->getRank();
  std::vector<GO> mine;
  if (me != 0) mine.push_back(0);
  for (GO i = me; i < kRows; i += p) mine.push_back(i);
  const Tpetra::global_size_t invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  const MultiVector X = filled(rcp(new Map(invalid, mine.data(), mine.size(), 0, comm)));
  if (p == 1) {
    expectRows(gatherRows(X, kAsked));
    return;
  }
  try {
    gatherRows(X, {5, 0});
    FAIL() << "no error for a row on " << p << " ranks";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("global id 0 is owned by " + std::to_string(p) + " ranks"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace gphr
