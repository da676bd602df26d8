// HDF5 round trips on 1 and 2 ranks: states written in parallel read back bit for bit, the file
// layout is rank-independent (global-id order), and bad files give errors naming the file.
#include <gtest/gtest.h>

#include <Teuchos_CommHelpers.hpp>
#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "TestUtils.hpp"
#include "gphr/core/Error.hpp"
#include "gphr/core/RankGroups.hpp"
#include "gphr/core/SnapshotSet.hpp"
#include "gphr/io/Hdf5File.hpp"

using namespace gphr;

namespace {

// Files of this run only: named after rank 0's pid and the rank count (test_hdf5 runs on 1 and 2
// ranks, possibly at the same time under ctest -j), and removed when the tests end.
std::vector<std::string>& createdFiles() {
  static std::vector<std::string> files;
  return files;
}
std::string tmpName(const std::string& base) {
  static const long id = [] {
    long pid = static_cast<long>(getpid());
    Teuchos::broadcast(*test::comm(), 0, Teuchos::outArg(pid));
    return pid;
  }();
  const std::string path =
      "/tmp/gphr_test_" + base + "_" + std::to_string(id) + "_np" + std::to_string(test::comm()->getSize()) + ".h5";
  if (std::find(createdFiles().begin(), createdFiles().end(), path) == createdFiles().end()) createdFiles().push_back(path);
  return path;
}
class RemoveCreatedFiles : public ::testing::Environment {
 public:
  void TearDown() override {
    test::comm()->barrier();
    if (test::comm()->getRank() == 0)
      for (const auto& f : createdFiles()) std::remove(f.c_str());
  }
};
[[maybe_unused]] ::testing::Environment* const removeCreatedFiles =
    ::testing::AddGlobalTestEnvironment(new RemoveCreatedFiles);

// `count` states on ps's map, state j filled by fillByGid with scale `first` + j and seed j.
MultiVector filledStates(const PhaseSpace& ps, size_t count, double first) {
  MultiVector states(ps.map(), count);
  for (size_t j = 0; j < count; ++j) test::fillByGid(*states.getVectorNonConst(j), first + j, j);
  return states;
}

// The largest entry of |states read from `name` - states| (0: read back bit for bit).
double maxStateDifference(const Hdf5File& f, const std::string& name, const PhaseSpace& ps, const MultiVector& states) {
  auto back = f.readStates(name, ps);
  back->update(-1.0, states, 1.0);
  std::vector<double> norms(states.getNumVectors());
  back->normInf(Teuchos::ArrayView<double>(norms));
  return *std::max_element(norms.begin(), norms.end());
}

TEST(Hdf5, ColumnsOnAContiguousMapRoundTripInGlobalOrder) {
  // A DEIM basis lives on the rows of G (a contiguous map): written in parallel, read back bit for
  // bit, and stored in global-row order (entry (j, g) is what a serial run holds at g).
  auto map = rcp(new Map(37, 0, test::comm()));
  MultiVector U(map, 3);
  for (size_t j = 0; j < 3; ++j) test::fillByGid(*U.getVectorNonConst(j), 1.0, j + 7);
  const std::string path = tmpName("columns");
  {
    Hdf5File f(path, test::comm(), Hdf5File::Mode::Create);
    f.writeColumns("U", U);
  }
  Hdf5File f(path, test::comm(), Hdf5File::Mode::ReadOnly);
  auto back = f.readColumns("U", map);
  ASSERT_EQ(back->getNumVectors(), 3u);
  back->update(-1.0, U, 1.0);
  std::vector<double> norms(3);
  back->normInf(Teuchos::ArrayView<double>(norms));
  for (double nrm : norms) EXPECT_EQ(nrm, 0.0);
  size_t rows = 0, cols = 0;
  const auto flat = f.readArray("U", &rows, &cols);
  ASSERT_EQ(rows, 3u);
  ASSERT_EQ(cols, 37u);
  Vector ref(rcp(new Map(37, 0, test::comm())));
  test::fillByGid(ref, 1.0, 8);
  auto rv = ref.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (LO i = 0; i < static_cast<LO>(map->getNodeNumElements()); ++i)
    EXPECT_EQ(flat[1 * 37 + map->getGlobalElement(i)], rv(i, 0));
  EXPECT_THROW(f.readColumns("U", rcp(new Map(36, 0, test::comm()))), InputError);  // wrong length
}

TEST(Hdf5, StatesRoundTripBitForBit) {
  PhaseSpace ps(23, test::comm());
  const MultiVector states = filledStates(ps, 4, 1.0);
  const std::string path = tmpName("states");
  {
    Hdf5File f(path, test::comm(), Hdf5File::Mode::Create);
    f.writeStates("traj", states, ps);
    f.writeArray("H", {1.0, 2.0, 3.0}, 3, 1);
    f.setAttribute("/", "scene", std::string("nls1d"));
    f.setAttribute("/traj", "parameters", std::vector<double>{1.0932});
  }
  Hdf5File f(path, test::comm(), Hdf5File::Mode::ReadOnly);
  EXPECT_EQ(maxStateDifference(f, "traj", ps, states), 0.0);
  EXPECT_EQ(f.readArray("H"), (std::vector<double>{1.0, 2.0, 3.0}));
  EXPECT_EQ(f.stringAttribute("/", "scene"), "nls1d");
  EXPECT_EQ(f.doubleAttribute("/traj", "parameters"), std::vector<double>{1.0932});
  // Global-id order in the file: entry (j, g) is the value a serial run would hold at g.
  size_t rows = 0, cols = 0;
  auto raw = f.readArray("traj", &rows, &cols);
  ASSERT_EQ(rows, 4u);
  ASSERT_EQ(cols, 46u);
  for (size_t g = 0; g < cols; ++g) {
    const double expected = std::sin(1.3 * g + 0.7 * 2 + 0.1 * double(g) * g / (1.0 + g)) * 3.0;
    EXPECT_DOUBLE_EQ(raw[2 * cols + g], expected);
  }
}

// Hdf5File::startWriteback (each seal of the artifacts file calls it, Linux sync_file_range) on a
// file open for writing, with data written and more to come, on every rank: the file reads back
// bit for bit afterwards, and what is written after the call is there too.
TEST(Hdf5, StartWritebackLeavesTheFileAsWritten) {
  PhaseSpace ps(23, test::comm());
  const MultiVector states = filledStates(ps, 3, 2.0);
  const std::string path = tmpName("writeback");
  {
    Hdf5File f(path, test::comm(), Hdf5File::Mode::Create);
    f.writeStates("traj", states, ps);
    f.startWriteback();
    f.setAttribute("/traj", "after", std::string("yes"));
  }
  Hdf5File f(path, test::comm(), Hdf5File::Mode::ReadOnly);
  EXPECT_EQ(maxStateDifference(f, "traj", ps, states), 0.0);
  EXPECT_EQ(f.stringAttribute("/traj", "after"), "yes");
}

// Every N-th state read alone (the DEIM basis uses every hyper.snapshotEvery-th): states 0, N, 2N,
// ... bit for bit, for N dividing the count and not; SnapshotSet::everyNth of held blocks gives the
// same columns.
TEST(Hdf5, EveryNthStateReadAlone) {
  PhaseSpace ps(23, test::comm());
  const MultiVector states = filledStates(ps, 7, 1.0);
  const std::string path = tmpName("strided");
  {
    Hdf5File f(path, test::comm(), Hdf5File::Mode::Create);
    f.writeStates("traj", states, ps);
  }
  Hdf5File f(path, test::comm(), Hdf5File::Mode::ReadOnly);
  const SnapshotSet held({rcp(new MultiVector(states, Teuchos::Copy))});
  for (size_t every : {1, 2, 3, 7, 9}) {
    const auto back = f.readStates("traj", ps, every);
    const auto view = held.everyNth(0, every);
    const size_t used = (7 + every - 1) / every;
    ASSERT_EQ(back->getNumVectors(), used) << "every " << every;
    ASSERT_EQ(view->getNumVectors(), used) << "every " << every;
    for (size_t u = 0; u < used; ++u) {
      Vector d(*back->getVector(u), Teuchos::Copy);
      d.update(-1.0, *states.getVector(u * every), 1.0);
      EXPECT_EQ(d.normInf(), 0.0) << "every " << every << ", state " << u * every;
      d.update(1.0, *view->getVector(u), -1.0, *back->getVector(u), 1.0);  // d = 0 + view - back
      EXPECT_EQ(d.normInf(), 0.0) << "held view, every " << every << ", state " << u * every;
    }
  }
  EXPECT_THROW(f.readStates("traj", ps, 0), InputError);
}

// A rank group's states written by its own ranks (writeStateRows; the training's groups): read
// back on all ranks they are the group's states bit for bit, for every group of every group size
// (each group's entries carry its number, so a row written by the wrong group shows).
TEST(Hdf5, StatesWrittenByOneRankGroup) {
  const auto world = test::comm();
  const PhaseSpace worldPs(23, world);
  const size_t count = 5;
  for (int size = 1; size <= world->getSize(); ++size) {
    const RankGroups g(world, size);
    const PhaseSpace groupPs(23, g.sub());
    auto fill = [&](MultiVector& X, int group) {
      for (size_t j = 0; j < count; ++j) test::fillByGid(*X.getVectorNonConst(j), 1.0 + j + 100.0 * group, j);
    };
    MultiVector mine(groupPs.map(), count);
    fill(mine, g.group());
    const std::string path = tmpName("groups" + std::to_string(size));
    {
      Hdf5File f(path, world, Hdf5File::Mode::Create);
      for (int from = 0; from < g.count(); ++from) {
        const bool ours = g.group() == from;
        f.createStates("g" + std::to_string(from), count, 46);
        f.writeStateRows("g" + std::to_string(from), 0, count, ours ? &mine : nullptr, ours ? &groupPs : nullptr);
      }
      f.createStates("bad", count, 46);
      EXPECT_THROW(f.writeStateRows("bad", 0, count, &mine, nullptr), InputError);
    }
    Hdf5File f(path, world, Hdf5File::Mode::ReadOnly);
    for (int from = 0; from < g.count(); ++from) {
      const auto back = f.readStates("g" + std::to_string(from), worldPs);
      MultiVector expected(worldPs.map(), count);
      fill(expected, from);
      ASSERT_EQ(back->getNumVectors(), count);
      back->update(-1.0, expected, 1.0);
      std::vector<double> err(count);
      back->normInf(Teuchos::ArrayView<double>(err));
      EXPECT_EQ(*std::max_element(err.begin(), err.end()), 0.0) << "group size " << size << ", group " << from;
    }
  }
}

// Column blocks (the training writes its states in blocks as it integrates them, the stages read
// them back in blocks): rows written block by block by one rank group (writeStateRows, blocks of
// 3, 3 and 1 of 7 states) equal the states bit for bit; a block read alone (readStates with a
// first row and a count, every 1 and every 2) is those states bit for bit, and SnapshotSet::columns
// of a held block the same columns; a range past the rows is refused by name.
TEST(Hdf5, ColumnBlocksWrittenAndReadAlone) {
  const auto world = test::comm();
  const PhaseSpace ps(23, world);
  const MultiVector states = filledStates(ps, 7, 1.0);
  const RankGroups g(world, 1);  // groups of one rank: group 0 writes, the others take part with nothing
  const PhaseSpace groupPs(23, g.sub());
  MultiVector mine(groupPs.map(), 7);
  for (size_t j = 0; j < 7; ++j) test::fillByGid(*mine.getVectorNonConst(j), 1.0 + j, j);
  const std::string path = tmpName("blocks");
  {
    Hdf5File f(path, world, Hdf5File::Mode::Create);
    f.createStates("traj", 7, 46);
    for (size_t first : {0u, 3u, 6u}) {
      const size_t b = std::min<size_t>(3, 7 - first);
      const auto block = mine.subView(Teuchos::Range1D(first, first + b - 1));
      const bool ours = g.group() == 0;
      f.writeStateRows("traj", first, b, ours ? block.get() : nullptr, ours ? &groupPs : nullptr);
    }
    EXPECT_THROW(f.writeStateRows("traj", 6, 2, nullptr, nullptr), InputError);  // rows 6, 7 of 7
  }
  Hdf5File f(path, world, Hdf5File::Mode::ReadOnly);
  const SnapshotSet held({rcp(new MultiVector(states, Teuchos::Copy))});
  for (size_t every : {1u, 2u})
    for (size_t first : {0u, 1u, 2u}) {
      const size_t count = 2;
      const auto back = f.readStates("traj", ps, every, first, count);
      const auto view = held.columns(0, every, first, count);
      ASSERT_EQ(back->getNumVectors(), count);
      ASSERT_EQ(view->getNumVectors(), count);
      for (size_t u = 0; u < count; ++u) {
        Vector d(*back->getVector(u), Teuchos::Copy);
        d.update(-1.0, *states.getVector((first + u) * every), 1.0);
        EXPECT_EQ(d.normInf(), 0.0) << "every " << every << ", state " << (first + u) * every;
        d.update(1.0, *view->getVector(u), -1.0, *back->getVector(u), 1.0);  // d = 0 + view - back
        EXPECT_EQ(d.normInf(), 0.0) << "held view, every " << every << ", state " << (first + u) * every;
      }
    }
  try {
    f.readStates("traj", ps, 2, 3, 2);  // rows 6 and 8 of the 4 every-2nd rows 0, 2, 4, 6
    ADD_FAILURE() << "a range past the rows was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("within its 4 such rows"), std::string::npos) << e.what();
  }
}

// An attribute past HDF5's 64 KiB limit for attributes in an object header (a fingerprint of
// 20,001 snapshots, 160 kB): the 1.8 file format gphr writes stores it densely, read back whole
// (the earliest format refuses it: "object header message is too large"), in a file gphr created
// and in a group gphr adds to a file in the earliest format (an older gphr's artifacts file).
TEST(Hdf5, AnAttributeLargerThan64KiBRoundTrips) {
  const std::string created = tmpName("large_attribute"), older = tmpName("large_attribute_older");
  if (test::comm()->getRank() == 0) {  // HDF5's defaults: the earliest format
    const hid_t id = H5Fcreate(older.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    ASSERT_GE(id, 0);
    H5Fclose(id);
  }
  test::comm()->barrier();
  std::vector<double> big(20001);
  for (size_t i = 0; i < big.size(); ++i) big[i] = std::sin(double(i));
  for (const auto& [path, mode] : {std::pair{created, Hdf5File::Mode::Create}, {older, Hdf5File::Mode::ReadWrite}}) {
    {
      Hdf5File f(path, test::comm(), mode);
      f.createGroup("/g");
      f.setAttribute("/g", "fingerprint", big);
      f.setAttribute("/g", "small", std::vector<double>{1.0});
    }
    const Hdf5File f(path, test::comm(), Hdf5File::Mode::ReadOnly);
    EXPECT_EQ(f.doubleAttribute("/g", "fingerprint"), big) << path;
    EXPECT_EQ(f.doubleAttribute("/g", "small"), std::vector<double>{1.0}) << path;
  }
}

TEST(Hdf5, BadFilesNameTheFile) {
  PhaseSpace ps(10, test::comm());
  const std::string junk = tmpName("junk");
  if (test::comm()->getRank() == 0) std::ofstream(junk) << "not hdf5";
  test::comm()->barrier();
  try {
    Hdf5File f(junk, test::comm(), Hdf5File::Mode::ReadOnly);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(junk), std::string::npos);
  }
  const std::string path = tmpName("mismatch");
  {
    Hdf5File f(path, test::comm(), Hdf5File::Mode::Create);
    MultiVector s(ps.map(), 2);
    f.writeStates("traj", s, ps);
  }
  PhaseSpace other(11, test::comm());
  Hdf5File f(path, test::comm(), Hdf5File::Mode::ReadOnly);
  EXPECT_THROW(f.readStates("traj", other), InputError);
  EXPECT_THROW(f.readStates("missing", ps), InputError);
}

}  // namespace
