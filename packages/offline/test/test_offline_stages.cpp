// The offline library on its own (no application): the training grid, the artifacts cache's
// rule (a dataset counts only with its key and its `complete` mark), a training resumed from the
// cache (bit-identical snapshots, unfinished parameters redone), and buildReducedModelFile's file
// loaded by the online library.
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>
#include <Teuchos_CommHelpers.hpp>
#include <hdf5.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <thread>
#include <tuple>
#include <malloc.h>
#include <unistd.h>

#include "gphr/core/Error.hpp"
#include "gphr/models/Scene.hpp"
#include "gphr/hyper/DeimBasis.hpp"
#include "gphr/offline/DeimBasisStage.hpp"
#include "gphr/offline/GreedyTraining.hpp"
#include "gphr/offline/ModelFileBuild.hpp"
#include "gphr/offline/OfflineSequence.hpp"
#include "gphr/offline/PodCheckpoint.hpp"
#include "gphr/reduction/SymplecticBasis.hpp"
#include "gphr/online/ReducedModel.hpp"
#include "gphr/timeint/FullModelIntegrator.hpp"

namespace gphr {
namespace {

// A directory shared by the ranks (rank 0's name), removed at the end.
class TempDir {
 public:
  TempDir() {
    auto comm = Tpetra::getDefaultComm();
    std::string name = (std::filesystem::temp_directory_path() / ("gphr_offline_" + std::to_string(::getpid()))).string();
    long len = static_cast<long>(name.size());
    Teuchos::broadcast(*comm, 0, &len);
    name.resize(len);
    Teuchos::broadcast(*comm, 0, static_cast<int>(len), name.data());
    path_ = name;
    if (comm->getRank() == 0) std::filesystem::create_directories(path_);
    comm->barrier();
  }
  ~TempDir() {
    Tpetra::getDefaultComm()->barrier();
    if (Tpetra::getDefaultComm()->getRank() == 0) std::filesystem::remove_all(path_);
  }
  std::string file(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

TrainingOptions smallTraining() {
  TrainingOptions o;
  o.parameters = {{0.9}, {1.0}, {1.1}};
  o.dt = 0.01;
  o.steps = 20;
  o.snapshotEvery = 2;
  o.progress = false;
  return o;
}

// The offline phase of the small training: basis size k, DEIM sizes ms (gp-deim unless changed).
ModelBuildOptions smallBuild(int k, std::vector<int> ms) {
  ModelBuildOptions o;
  o.training = smallTraining();
  o.basis.k = k;
  o.ms = std::move(ms);
  return o;
}

TEST(TrainingGrid, TensorGridFirstParameterFastest) {
  ParameterBox box;
  box.names = {"a", "b"};
  box.bounds = {{0.0, 1.0}, {2.0, 4.0}};
  box.enters = {EntersRowKernel, EntersRowKernel};
  const auto g = trainingGrid(box, {3, 2});
  ASSERT_EQ(g.size(), 6u);
  EXPECT_EQ(g[0], (std::vector<double>{0.0, 2.0}));
  EXPECT_EQ(g[1], (std::vector<double>{0.5, 2.0}));
  EXPECT_EQ(g[2], (std::vector<double>{1.0, 2.0}));
  EXPECT_EQ(g[5], (std::vector<double>{1.0, 4.0}));
  EXPECT_EQ(trainingGrid(box, {1, 1}), (std::vector<std::vector<double>>{{0.5, 3.0}}));  // midpoints
  EXPECT_THROW(trainingGrid(box, {3}), InputError);                                      // one count per parameter
  EXPECT_THROW(trainingGrid(box, {0, 2}), InputError);
}

// The default training group size is the documented rule: the group count G with the least
// ceil(P / G) / floor(p / G) among the groups keeping 4096 .. 2^18 state rows per rank (Training.hpp).
TEST(TrainingGrid, GroupSizeOnePerParameterWithinTheRowBounds) {
  EXPECT_EQ(trainingGroupSize(4096, 16, 5), 1);       // NLS n = 2048: a system is not worth splitting
  EXPECT_EQ(trainingGroupSize(131072, 16, 4), 4);     // SWE 256^2: a group of 4 per parameter
  EXPECT_EQ(trainingGroupSize(131072, 2, 4), 1);      // fewer ranks than parameters: one rank each
  EXPECT_EQ(trainingGroupSize(131072, 16, 1), 16);    // one parameter: all ranks (32 would be worth it)
  EXPECT_EQ(trainingGroupSize(3L << 18, 15, 5), 3);   // 3 x 2^18 rows: 5 groups of 3 tie 1 of 15; more groups
  EXPECT_EQ(trainingGroupSize(3L << 18, 16, 25), 16); // 25 rounds on 16 ranks beat 5 rounds on 3 (1.56 < 1.67)
  EXPECT_EQ(trainingGroupSize(1L << 30, 16, 25), 16); // more than 16 x 2^18 rows: all ranks, the most there are
  EXPECT_EQ(trainingGroupSize(100, 1, 3), 1);
  EXPECT_EQ(trainingGroupSize(100000000, 1024, 5), 1024);  // 2 groups of 512: 3 rounds, 3 / 512 > 5 / 1024
  EXPECT_EQ(trainingGroupSize(131072, 12, 8), 3);  // 4 groups of 3, 2 rounds (2 / 3), not 8 of 1 (1 / 1)
}

TEST(ArtifactsCache, ADatasetCountsOnlyWithItsKeyAndMark) {
  auto comm = Tpetra::getDefaultComm();
  TempDir dir;
  const ArtifactsCache cache(dir.file("a.h5"), comm, "nls1d", 64);
  {
    auto f = cache.open();
    ArtifactsCache::clear(*f, "/stage/x");
    f->writeArray("/stage/x", {1.0, 2.0}, 1, 2);
    f->setAttribute("/stage/x", "config", std::string("key 1"));  // a kill before the mark
    EXPECT_FALSE(ArtifactsCache::holds(*f, "/stage/x", "key 1"));
    cache.seal(*f, "/stage/x", "key 1");
    EXPECT_TRUE(ArtifactsCache::holds(*f, "/stage/x", "key 1"));
    EXPECT_FALSE(ArtifactsCache::holds(*f, "/stage/x", "key 2"));
    EXPECT_FALSE(ArtifactsCache::holds(*f, "/stage/y", "key 1"));
  }
  EXPECT_NO_THROW(ArtifactsCache(dir.file("a.h5"), comm, "nls1d", 64));
  EXPECT_THROW(ArtifactsCache(dir.file("a.h5"), comm, "swe2d", 64), InputError);  // another scene
  EXPECT_THROW(ArtifactsCache(dir.file("a.h5"), comm, "nls1d", 80), InputError);  // another size
}

double maxDifference(const MultiVector& a, const MultiVector& b);

// trainingSystems makes each system when asked for and keeps two alive (the first and the last
// asked for): P of them held at once grew the DEIM stage's memory with the training set. Each made
// system is the scene's instance at its parameter (the same gradient of G, exactly: the same
// arithmetic). Liveness is read through weak references.
TEST(TrainingSystems, MadeWhenAskedTwoAliveAtATime) {
  auto comm = Tpetra::getDefaultComm();
  const Nls1d scene(64);
  TrainingResult t;
  t.parameters = {{0.9}, {0.95}, {1.0}, {1.05}, {1.1}};
  const SystemSet set = trainingSystems(scene, comm, t);
  ASSERT_EQ(set.size(), 5u);
  std::vector<RCP<const HamiltonianSystem>> weak;
  for (size_t j = 0; j < set.size(); ++j) {
    weak.push_back(set[j].create_weak());
    const auto eager = scene.instantiate(comm, t.parameters[j], true).system;
    Vector y(eager->map()), mine(eager->map()), theirs(eager->map());
    y.randomize();
    set[j]->nonlinearGradient(y, mine);
    eager->nonlinearGradient(y, theirs);
    theirs.update(-1.0, mine, 1.0);
    EXPECT_EQ(theirs.normInf(), 0.0) << "system " << j;
  }
  std::vector<int> alive;
  for (size_t j = 0; j < weak.size(); ++j) alive.push_back(weak[j].is_valid_ptr() ? 1 : 0);
  EXPECT_EQ(alive, (std::vector<int>{1, 0, 0, 0, 1}));
  EXPECT_EQ(set[0].get(), weak[0].get());  // the first is kept, not made again
}

// PodCheckpoint's rule: of two slots written in turn, a restart takes the complete one that got
// furthest below the limit asked, its state read back exactly (the same doubles); a slot whose
// mark is gone (a kill while it was rewritten) leaves the other; another key, none; clear() removes
// the file; within the cache's checkpoint interval nothing is written. On 1-3 ranks (each rank its
// own rows of U).
TEST(PodCheckpoint, TakesTheFurthestCompleteSlotExactly) {
  auto comm = Tpetra::getDefaultComm();
  TempDir dir;
  ArtifactsCache cache(dir.file("a.h5"), comm, "nls1d", 64);
  cache.setCheckpointSeconds(0.0);  // every write is due
  const RCP<const Map> map = rcp(new Map(37, 0, comm));
  auto stateAt = [&](int progress) {  // a state whose numbers say which progress it was saved at
    StreamingPod::State st;
    auto U = rcp(new MultiVector(map, 3));
    U->randomize();
    st.U = U;
    st.sigma = {3.0 + progress, 2.0, 1.0 / 3.0};
    st.energy = 10.0 * progress, st.columns = 8 * progress, st.steps.stacked = progress;
    return st;
  };
  const StreamingPod::State one = stateAt(1), two = stateAt(2);
  PodCheckpoint cp(&cache, "/stage/x", "key 1");
  EXPECT_TRUE(cp.write(one, PodProgress{1, {0.5}}));
  EXPECT_TRUE(cp.write(two, PodProgress{2, {0.25}}));
  StreamingPod::State back;
  PodProgress at = PodCheckpoint(&cache, "/stage/x", "key 1").read(map, 1, 5, back);
  ASSERT_EQ(at.progress, 2);
  EXPECT_EQ(at.extra, std::vector<double>{0.25});
  EXPECT_EQ(back.sigma, two.sigma);
  EXPECT_EQ(back.energy, two.energy);
  EXPECT_EQ(back.columns, two.columns);
  EXPECT_EQ(back.steps.stacked, 2);
  EXPECT_EQ(maxDifference(*back.U, *two.U), 0.0);
  // progress 2 is not below a limit of 2 (a result of 2 blocks is complete, not resumed)
  EXPECT_EQ(PodCheckpoint(&cache, "/stage/x", "key 1").read(map, 1, 2, back).progress, 1);
  EXPECT_EQ(PodCheckpoint(&cache, "/stage/x", "key 2").read(map, 1, 5, back).progress, 0);  // another key
  {  // slot 1 (progress 2) loses its mark, as a kill while rewriting it would leave it
    Hdf5File f(cp.path(), comm, Hdf5File::Mode::ReadWrite);
    f.setAttribute("/slot1", "config", std::string("being rewritten"));
  }
  at = PodCheckpoint(&cache, "/stage/x", "key 1").read(map, 1, 5, back);
  ASSERT_EQ(at.progress, 1);
  EXPECT_EQ(back.sigma, one.sigma);
  EXPECT_EQ(maxDifference(*back.U, *one.U), 0.0);
  comm->barrier();
  if (comm->getRank() == 0) {  // slot 0 (progress 1): one value of U changed in place, its marks kept
    const hid_t f = H5Fopen(cp.path().c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t d = H5Dopen2(f, "/slot0", H5P_DEFAULT), space = H5Dget_space(d);
    const hsize_t at2[2] = {1, 20}, one1[1] = {1};
    const hid_t mem = H5Screate_simple(1, one1, nullptr);
    H5Sselect_elements(space, H5S_SELECT_SET, 1, at2);
    const double changed = 42.0;
    EXPECT_GE(H5Dwrite(d, H5T_NATIVE_DOUBLE, mem, space, H5P_DEFAULT, &changed), 0);
    H5Sclose(mem), H5Sclose(space), H5Dclose(d), H5Fclose(f);
  }
  comm->barrier();
  // no longer matching its fingerprint: not resumed from (said on stderr), the stage starts afresh
  EXPECT_EQ(PodCheckpoint(&cache, "/stage/x", "key 1").read(map, 1, 5, back).progress, 0);
  EXPECT_TRUE(std::filesystem::exists(cp.path()));
  cp.clear();
  EXPECT_FALSE(std::filesystem::exists(cp.path()));
  EXPECT_EQ(PodCheckpoint(&cache, "/stage/x", "key 1").read(map, 1, 5, back).progress, 0);
  // Before the cache's interval has passed since it was made (an hour here), a checkpoint is not
  // written, on any rank (rank 0's clock decides): no file, nothing to resume from.
  cache.setCheckpointSeconds(3600.0);
  PodCheckpoint rare(&cache, "/stage/x", "key 1");
  EXPECT_FALSE(rare.write(one, PodProgress{1, {0.5}}));
  EXPECT_FALSE(std::filesystem::exists(rare.path()));
  EXPECT_THROW(cache.setCheckpointSeconds(-1.0), InputError);
}

// Removing the artifacts file is the way to start afresh: its checkpoints, PODs of its snapshots
// under a configuration key the new run may share, go with it when the new file is created (here a
// checkpoint under the same key would otherwise be resumed from, at progress 1).
TEST(PodCheckpoint, AFreshArtifactsFileStartsWithoutThem) {
  auto comm = Tpetra::getDefaultComm();
  TempDir dir;
  const RCP<const Map> map = rcp(new Map(37, 0, comm));
  StreamingPod::State st;
  st.U = rcp(new MultiVector(map, 2));
  st.sigma = {2.0, 1.0};
  std::string kept;
  {
    ArtifactsCache cache(dir.file("a.h5"), comm, "nls1d", 64);
    cache.setCheckpointSeconds(0.0);
    PodCheckpoint cp(&cache, "/stage/x", "key 1");
    ASSERT_TRUE(cp.write(st, PodProgress{1, {}}));
    kept = cp.path();
    ArtifactsCache again(dir.file("a.h5"), comm, "nls1d", 64);  // the file is there: its checkpoint stays
    ASSERT_TRUE(std::filesystem::exists(kept));
  }
  comm->barrier();
  if (comm->getRank() == 0) std::filesystem::remove(dir.file("a.h5"));
  comm->barrier();
  ArtifactsCache fresh(dir.file("a.h5"), comm, "nls1d", 64);
  EXPECT_FALSE(std::filesystem::exists(kept));
  StreamingPod::State back;
  EXPECT_EQ(PodCheckpoint(&fresh, "/stage/x", "key 1").read(map, 0, 5, back).progress, 0);
}

double maxDifference(const MultiVector& a, const MultiVector& b) {
  MultiVector d(a, Teuchos::Copy);
  d.update(-1.0, b, 1.0);
  std::vector<double> n(d.getNumVectors());
  d.normInf(n);
  return *std::max_element(n.begin(), n.end());
}

// The NLS with n = 32 and an artifacts cache for it in a directory of its own.
struct SmallScene {
  RCP<const Comm> comm = Tpetra::getDefaultComm();
  TempDir dir;
  Nls1d scene{32};
  ArtifactsCache cache{dir.file("a.h5"), comm, scene.name(), 64};
};

TEST(Training, ResumedFromTheCacheBitForBit) {
  const SmallScene small;
  const auto& [comm, dir, scene, cache] = small;
  TrainingOptions o = smallTraining();
  o.groupSize = comm->getSize();  // all ranks together, as without a cache: bit for bit below
  const TrainingResult first = runTraining(scene, comm, o, &cache, "key");
  ASSERT_EQ(first.snapshots.size(), 3u);
  EXPECT_EQ(first.snapshots[0]->getNumVectors(), 11u);  // states 0, 2, ..., 20
  EXPECT_EQ(first.reused, 0);
  {  // parameter 1 as a killed run leaves it: written, not sealed
    auto f = cache.open();
    ArtifactsCache::clear(*f, "/training/p1");
    f->writeStates("/training/p1", *first.snapshots[0], PhaseSpace(32, comm));
  }
  const TrainingResult again = runTraining(scene, comm, o, &cache, "key");
  EXPECT_EQ(again.reused, 2);  // p0 and p2; p1 redone
  for (size_t j = 0; j < 3; ++j) EXPECT_EQ(maxDifference(*again.snapshots[j], *first.snapshots[j]), 0.0) << j;
  const TrainingResult other = runTraining(scene, comm, o, &cache, "another key");  // trains again
  EXPECT_EQ(other.reused, 0);
  const TrainingResult none = runTraining(scene, comm, o);  // no cache: the same snapshots
  EXPECT_EQ(maxDifference(*none.snapshots[2], *first.snapshots[2]), 0.0);
}

// The cache's key is of the trajectories' settings; each parameter's states are kept with its own
// values: a set grown by a parameter trains that one only (what a greedy training adds each round),
// and a set whose parameter changed retrains that one only.
TEST(Training, AGrownSetTrainsItsNewParametersOnly) {
  const SmallScene small;
  const auto& [comm, dir, scene, cache] = small;
  TrainingOptions o = smallTraining();
  o.groupSize = comm->getSize();
  const TrainingResult first = runTraining(scene, comm, o, &cache, "key");
  o.parameters.push_back({0.95});
  const TrainingResult grown = runTraining(scene, comm, o, &cache, "key");
  EXPECT_EQ(grown.reused, 3);
  ASSERT_EQ(grown.snapshots.size(), 4u);
  for (size_t j = 0; j < 3; ++j) EXPECT_EQ(maxDifference(*grown.snapshots[j], *first.snapshots[j]), 0.0) << j;
  TrainingOptions alone = o;
  alone.parameters = {{0.95}};
  EXPECT_EQ(maxDifference(*grown.snapshots[3], *runTraining(scene, comm, alone).snapshots[0]), 0.0);
  o.parameters[1] = {1.05};  // another value at index 1: that one is trained again, the others kept
  const TrainingResult changed = runTraining(scene, comm, o, &cache, "key");
  EXPECT_EQ(changed.reused, 3);
  alone.parameters = {{1.05}};
  EXPECT_EQ(maxDifference(*changed.snapshots[1], *runTraining(scene, comm, alone).snapshots[0]), 0.0);
  o.parameters.pop_back();  // a shorter set: the dataset past its end is dropped, the rest kept
  const TrainingResult shorter = runTraining(scene, comm, o, &cache, "key");
  EXPECT_EQ(shorter.reused, 3);
  EXPECT_FALSE(cache.open()->exists("/training/p3"));
}

TEST(Training, HeldInMemoryAcrossBlocksAsInTheCache) {
  // 151 states: three of integrateInBlocks' blocks (64, 64, 23); the training without a cache
  // gathers them into one MultiVector, the cached one writes them block by block: the same numbers.
  const SmallScene small;
  const auto& [comm, dir, scene, cache] = small;
  TrainingOptions o = smallTraining();
  o.parameters = {{1.0}};
  o.steps = 150, o.snapshotEvery = 1;
  o.groupSize = comm->getSize();
  ASSERT_GT(static_cast<size_t>(o.steps + 1), 2 * kSnapshotReadColumns);
  const TrainingResult cached = runTraining(scene, comm, o, &cache, "key");
  const TrainingResult held = runTraining(scene, comm, o);
  ASSERT_EQ(held.snapshots[0]->getNumVectors(), 151u);
  EXPECT_EQ(maxDifference(*held.snapshots[0], *cached.snapshots[0]), 0.0);
  // and both are the full model's states, in order: the integrator run directly, every state kept
  const SceneInstance inst = scene.instantiate(comm, o.parameters[0], true);
  FullModelIntegrator integ(inst.system, o.integrator);
  MultiVector direct(inst.system->map(), 151);
  Vector y(*inst.y0, Teuchos::Copy);
  integ.run(y, o.dt, o.steps, [&](long s, double, const Vector& ys, const StepReport&) {
    Tpetra::deep_copy(*direct.getVectorNonConst(s), ys);
  });
  EXPECT_EQ(maxDifference(*held.snapshots[0], direct), 0.0);
}

// Rewrites parameter `name`'s states as `X`, sealed for `key`, with the fingerprint `print` (none
// when empty): what a changed file, or an older gphr's, holds.
void rewriteParameter(const ArtifactsCache& cache, const std::string& name, const MultiVector& X,
                      const std::vector<double>& print, const std::string& key) {
  auto f = cache.open();
  const std::vector<double> mu = f->doubleAttribute(name, "parameters");
  ArtifactsCache::clear(*f, name);
  f->writeStates(name, X, PhaseSpace(static_cast<GO>(X.getGlobalLength() / 2), X.getMap()->getComm()));
  f->setAttribute(name, "parameters", mu);
  if (!print.empty()) ArtifactsCache::stampFingerprint(*f, name, print);
  cache.seal(*f, name, key);
}

// The message of the InputError `read` throws ("" if none).
template <class Read>
std::string readError(Read read) {
  try {
    read();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// The training's snapshots carry the fingerprint of their columns (ColumnFingerprint.hpp), each
// parameter's stamped by the group that integrated it (groups of one rank on 2 and 3 ranks): read
// back on all ranks they match it. An entry changed in the file is refused by every read that
// holds its column, naming parameter and column; a strided read that skips that column is not.
// A parameter sealed without a fingerprint (an older gphr's) is trained again.
// The training integrates through the one observed loop: a full model that fails is the training's
// error, named as such with the step's reason, and nothing of it is kept as a snapshot.
TEST(Training, AFullModelThatFailsIsTheTrainingsErrorWithItsReason) {
  const SmallScene small;
  const auto& [comm, dir, scene, cache] = small;
  TrainingOptions o = smallTraining();
  // The tightest tolerance allowed in one Newton iteration: a nonlinear step's first update from the
  // previous state leaves a residual far above 1e-15.
  o.integrator.set("newtonTolerance", 1e-15);
  o.integrator.set("maxNewtonIterations", 1);
  try {
    runTraining(scene, comm, o);
    ADD_FAILURE() << "a training whose full model failed returned";
  } catch (const SolverError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("training parameter 1 of 3: the full model failed: Newton did not converge"), std::string::npos)
        << what;
  }
}

TEST(Training, AChangedSnapshotIsRefusedWhereItIsRead) {
  const SmallScene small;
  const auto& [comm, dir, scene, cache] = small;
  TrainingOptions o = smallTraining();
  o.groupSize = 1;
  const TrainingResult first = runTraining(scene, comm, o, &cache, "key");
  for (size_t j = 0; j < 3; ++j) EXPECT_EQ(readError([&] { first.snapshots[j]; }), "") << j;
  const MultiVector clean(*first.snapshots[1], Teuchos::Copy);
  MultiVector changed(clean, Teuchos::Copy);
  const GO row = 40;  // on the last rank on 2 and 3 ranks
  if (changed.getMap()->isNodeGlobalElement(row)) changed.sumIntoGlobalValue(row, 5, 0.5);
  std::vector<double> print;
  {
    auto f = cache.open();
    print = f->doubleAttribute("/training/p1", "fingerprint");
  }
  ASSERT_EQ(print.size(), 11u);
  rewriteParameter(cache, "/training/p1", changed, print, "key");
  const TrainingResult again = runTraining(scene, comm, o, &cache, "key");
  EXPECT_EQ(again.reused, 3);
  const std::string all = readError([&] { again.snapshots[1]; });
  EXPECT_NE(all.find("training parameter 2 (/training/p1): column 5 does not match its fingerprint"),
            std::string::npos) << all;
  EXPECT_NE(all.find("to train afresh"), std::string::npos) << all;
  EXPECT_NE(readError([&] { again.snapshots.columns(1, 1, 4, 3); }).find("column 5 does"), std::string::npos);
  EXPECT_NE(readError([&] { again.snapshots.columns(1, 5, 1, 1); }).find("column 5 does"), std::string::npos);
  EXPECT_EQ(readError([&] { again.snapshots.everyNth(1, 2); }), "");  // states 0, 2, ..., 10
  EXPECT_EQ(readError([&] { again.snapshots[0]; }), "");
  rewriteParameter(cache, "/training/p1", clean, {}, "key");
  EXPECT_EQ(runTraining(scene, comm, o, &cache, "key").reused, 2);
}

// Rank groups give the snapshots all ranks together give, to round-off: with groups of one rank
// each parameter is integrated on one rank (its own order of sums in GMRES and the norms), so the
// states differ by the Newton tolerance (1e-10 on ||R||) per step at most; over 20 steps of states
// of norm ~3 a relative 1e-8 bounds it. Both land in the cache in parameter order.
// Five values of eps on groups of `groupSize` ranks.
TrainingOptions fiveParameters(int groupSize) {
  TrainingOptions o = smallTraining();
  o.parameters = {{0.9}, {0.95}, {1.0}, {1.05}, {1.1}};
  o.groupSize = groupSize;
  return o;
}

TEST(Training, RankGroupsGiveTheSameSnapshots) {
  auto comm = Tpetra::getDefaultComm();
  TempDir dir;
  const Nls1d scene(64);
  TrainingOptions o = smallTraining();
  o.parameters = {{0.9}, {0.95}, {1.0}, {1.05}, {1.1}};
  o.groupSize = comm->getSize();
  const ArtifactsCache together(dir.file("together.h5"), comm, scene.name(), 128);
  const TrainingResult one = runTraining(scene, comm, o, &together, "key");
  o.groupSize = 1;
  const ArtifactsCache grouped(dir.file("grouped.h5"), comm, scene.name(), 128);
  const TrainingResult groups = runTraining(scene, comm, o, &grouped, "key");
  ASSERT_EQ(groups.snapshots.size(), 5u);
  // On one rank both runs are one group of one rank: only the resume below is checked there.
  for (size_t j = 0; j < 5 && comm->getSize() > 1; ++j) {
    const auto a = one.snapshots[j], b = groups.snapshots[j];
    std::vector<double> n(a->getNumVectors());
    a->normInf(n);
    EXPECT_LE(maxDifference(*a, *b), 1e-8 * *std::max_element(n.begin(), n.end())) << "parameter " << j;
  }
  EXPECT_EQ(runTraining(scene, comm, o, &grouped, "key").reused, 5);  // resumed: every parameter kept
}

// Parameters appended to a trained set (a greedy round's) are integrated side by side by the rank
// groups, each on the group it has in a whole training (parameter c on group c mod G): one round
// for two new parameters on 2 and 3 ranks (two on 1), and the same bits as the whole training.
TEST(Training, AppendedParametersGoSideBySideOnTheirOwnGroups) {
  auto comm = Tpetra::getDefaultComm();
  TempDir dir;
  const Nls1d scene(64);
  TrainingOptions o = fiveParameters(1);
  const ArtifactsCache whole(dir.file("whole.h5"), comm, scene.name(), 128);
  const TrainingResult all = runTraining(scene, comm, o, &whole, "key");
  EXPECT_EQ(all.rounds, (5 + comm->getSize() - 1) / comm->getSize());
  const ArtifactsCache grown(dir.file("grown.h5"), comm, scene.name(), 128);
  TrainingOptions first = o;
  first.parameters.resize(3);
  EXPECT_EQ(runTraining(scene, comm, first, &grown, "key").reused, 0);
  const TrainingResult more = runTraining(scene, comm, o, &grown, "key");
  EXPECT_EQ(more.reused, 3);
  EXPECT_EQ(more.rounds, comm->getSize() == 1 ? 2 : 1);  // parameters 3 and 4: groups 3 mod G and 4 mod G
  for (size_t j = 0; j < 5; ++j) EXPECT_EQ(maxDifference(*more.snapshots[j], *all.snapshots[j]), 0.0) << j;
}

// The DEIM basis stage over rank groups (each chunk of the hierarchical POD on one group's ranks)
// gives the basis all ranks together give: the chunks are the same, only the order of the sums in
// each step's QR differs. Compared as U diag(sigma^2) U^T applied to a few vectors (blind to signs
// and to rotations inside clusters of equal sigma): the steps' round-off is a few eps sigma_1^2
// each (~40 steps here), so 1e-11 sigma_1^2 leaves a margin of ~20x.
TEST(DeimBasisStage, RankGroupsGiveTheBasisAllRanksGive) {
  auto comm = Tpetra::getDefaultComm();
  if (comm->getSize() == 1) GTEST_SKIP() << "one rank: groups of one rank are all ranks together";
  TempDir dir;
  const Nls1d scene(64);
  TrainingOptions o = fiveParameters(1);
  const ArtifactsCache cache(dir.file("a.h5"), comm, scene.name(), 128);
  const TrainingResult training = runTraining(scene, comm, o, &cache, "key");
  const auto inst = scene.instantiate(comm, training.parameters[0], true);
  BasisOptions b;
  b.k = 4;
  const ReducedBasis basis = computeSymplecticBasis(training.snapshots, inst.system->space(), b);
  DeimBasisOptions d;
  d.maxRank = 12;
  d.chunkSnapshots = 4;  // 55 snapshots: 14 chunks, shared by the groups
  d.groupSize = 1;
  const DeimBasis grouped = runDeimBasisStage(scene, comm, training, *basis.A, *inst.system, d).basis;
  d.groupSize = comm->getSize();  // one group: every chunk on all ranks
  const DeimBasis together = runDeimBasisStage(scene, comm, training, *basis.A, *inst.system, d).basis;
  ASSERT_EQ(grouped.singularValues.size(), together.singularValues.size());
  const double s1 = together.singularValues[0];
  for (size_t j = 0; j < together.singularValues.size(); ++j)
    EXPECT_NEAR(grouped.singularValues[j], together.singularValues[j], 1e-12 * s1) << j;
  EXPECT_EQ(grouped.snapshots, 55);
  EXPECT_NEAR(grouped.energy, together.energy, 1e-12 * together.energy);
  auto weighted = [](const DeimBasis& e, const MultiVector& x) {  // U diag(sigma^2) U^T x
    auto local = rcp(new Map(e.singularValues.size(), 0, x.getMap()->getComm(), Tpetra::LocallyReplicated));
    MultiVector c(local, x.getNumVectors());
    c.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, *e.U, x, 0.0);
    {
      auto v = c.getLocalViewHost(Tpetra::Access::ReadWrite);
      for (size_t i = 0; i < e.singularValues.size(); ++i)
        for (size_t j = 0; j < x.getNumVectors(); ++j) v(i, j) *= e.singularValues[i] * e.singularValues[i];
    }
    MultiVector y(x.getMap(), x.getNumVectors());
    y.multiply(Teuchos::NO_TRANS, Teuchos::NO_TRANS, 1.0, *e.U, c, 0.0);
    return y;
  };
  MultiVector x(together.U->getMap(), 3);
  x.randomize();
  const MultiVector a = weighted(together, x), g = weighted(grouped, x);
  std::vector<double> n(3);
  x.norm2(n);
  EXPECT_LE(maxDifference(a, g), 1e-11 * s1 * s1 * *std::max_element(n.begin(), n.end()));
}

// The heap in use (glibc's count of allocated bytes: what this process holds, not what it maps).
double heapBytes() { return static_cast<double>(mallinfo2().uordblks); }

// The largest heap growth while the basis and the DEIM basis stages read the snapshots, over the
// heap before them (the training systems already built: one per parameter, O(n) each, not
// snapshots), sampled as each block is read: the moment the most blocks can be alive.
double peakGrowthOfStages(const Nls1d& scene, const TrainingResult& training) {
  auto comm = Tpetra::getDefaultComm();
  const auto systems = trainingSystems(scene, comm, training);
  const auto inst = scene.instantiate(comm, training.parameters[0], true);
  std::vector<size_t> columns;
  for (size_t j = 0; j < training.snapshots.size(); ++j) columns.push_back(training.snapshots.numColumns(j));
  double peak = 0.0;
  const double before = heapBytes();
  const SnapshotSet watched(columns, [&](size_t j, size_t every, size_t first, size_t count) {
    auto block = count == SnapshotSet::kAll ? training.snapshots.everyNth(j, every)
                                            : training.snapshots.columns(j, every, first, count);
    peak = std::max(peak, heapBytes() - before);
    return block;
  });
  BasisOptions b;
  b.k = 4;
  const ReducedBasis basis = computeSymplecticBasis(watched, inst.system->space(), b);
  DeimBasisOptions d;
  d.maxRank = 8;
  computeDeimBasis(systems, watched, *basis.A, d);
  return peak;
}

// Streamed from the cache, the stages after training read the states in column blocks: six
// training parameters cost what two cost (within 1.2x; held in memory they cost about
// three times as much, each parameter 2n x 401 doubles, 3.3 MB on one rank), and trajectories 4x
// as long add far less than the 1200 more states of one parameter on this rank's rows, which a
// stage reading a parameter at a time holds (9.8 MB on one rank, 3.3 MB on each of three): at most
// a quarter of it. (What does grow with the states is small: their reduced coordinates, 2k = 8
// numbers each, and the MPI library's own buffers, a few 100 kB on 2-3 ranks, which is why the
// long case is bounded by the held states' size rather than by a ratio of two small growths.)
// Both bounds allow the basis POD's step array, which the POD keeps from step to step (the leaf's
// rows x (carried + new) columns: 2 (2k + 32) + 2 blockColumns = 336 here, 2.75 MB on one rank):
// its size is set by the options, not by the snapshots; it shows once the POD's rank reaches its
// cap, which the longer trainings reach and the 2 x 400 one does not.
TEST(Training, TheStagesAfterItHoldOneColumnBlockAtATime) {
  auto comm = Tpetra::getDefaultComm();
  TempDir dir;
  const Nls1d scene(512);
  std::vector<double> growth;
  const std::vector<std::pair<size_t, int>> cases = {{2, 400}, {6, 400}, {2, 1600}};  // parameters, steps
  for (const auto& [count, steps] : cases) {
    TrainingOptions o = smallTraining();
    o.steps = steps;
    o.snapshotEvery = 1;
    o.parameters.clear();
    for (size_t j = 0; j < count; ++j) o.parameters.push_back({0.9 + 0.2 * j / (count - 1)});
    const ArtifactsCache cache(dir.file("a" + std::to_string(count) + "_" + std::to_string(steps) + ".h5"), comm,
                               scene.name(), 1024);
    const TrainingResult t = runTraining(scene, comm, o, &cache, "key");
    ASSERT_TRUE(t.snapshots.streamed());
    growth.push_back(peakGrowthOfStages(scene, t));
  }
  std::printf("peak heap growth while the stages read the snapshots: %.0f B (2 parameters), %.0f B (6 parameters), "
              "%.0f B (2 parameters, 4x the steps)\n", growth[0], growth[1], growth[2]);
  const double rows = static_cast<double>(scene.instantiate(comm, {1.0}, true).system->map()->getNodeNumElements());
  const double podArray = rows * (2.0 * (2 * 4 + 32) + 2.0 * BasisOptions().blockColumns) * sizeof(double);
  EXPECT_LE(growth[1], 1.2 * growth[0] + podArray) << "peak heap growth " << growth[0] << " B (2 parameters), "
                                                   << growth[1] << " B (6 parameters)";
  const double heldExtra = (1601.0 - 401.0) * rows * sizeof(double);  // one parameter's extra states, held
  EXPECT_LE(growth[2] - growth[0], 0.25 * heldExtra + podArray)
      << "peak heap growth " << growth[0] << " B (400 steps), " << growth[2] << " B (1600 steps): the 1200 more "
      << "states of one parameter are " << heldExtra << " B on this rank";
}

// A training parameter whose full model fails (Newton: 4 iterations at most, tolerance 3e-13, dt =
// 0.5: after its first step's 4 iterations eps = 0.9 is at a residual of 1.7e-14 and eps = 1.1 at
// 6.5e-12, a factor of ~20 on either side of the tolerance) ends the training on every rank with
// one SolverError naming it, in groups of one rank too: the other groups, which finish, are not
// left waiting in a block write for the group that stopped (they were, before: a hang).
TEST(Training, AFailedParameterEndsItOnEveryRank) {
  auto comm = Tpetra::getDefaultComm();
  TempDir dir;
  const Nls1d scene(64);
  TrainingOptions o = smallTraining();
  o.parameters = {{0.9}, {1.1}};
  o.dt = 0.5;
  o.steps = 1;
  o.snapshotEvery = 1;
  o.groupSize = 1;
  o.integrator.set("maxNewtonIterations", 4);
  o.integrator.set("newtonTolerance", 3e-13);
  const ArtifactsCache cache(dir.file("fail.h5"), comm, scene.name(), 128);
  try {
    runTraining(scene, comm, o, &cache, "key");
    ADD_FAILURE() << "the training of a parameter whose Newton fails went through";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("training parameter 2 of 2: the full model failed: Newton did not converge"),
              std::string::npos)
        << e.what();
  }
  int everyRank = 1, all = 0;  // every rank got here: none is still waiting
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, everyRank, Teuchos::outArg(all));
  EXPECT_EQ(all, comm->getSize());
}

// The peak of the heap in use (malloc's bytes, both from its arenas and mmap'ed) over `work`,
// above the heap before it: a thread samples it every 0.2 ms. A block of states held for the
// whole integration (seconds) is seen by thousands of samples.
template <class Work>
double peakHeapGrowthOf(Work&& work) {
  auto inUse = [] {
    const struct mallinfo2 m = mallinfo2();
    return static_cast<double>(m.uordblks + m.hblkhd);
  };
  const double before = inUse();
  std::atomic<bool> stop{false};
  std::atomic<double> peak{0.0};
  std::thread sampler([&] {
    while (!stop.load()) {
      const double g = inUse() - before;
      if (g > peak.load()) peak.store(g);
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  });
  work();
  stop.store(true);
  sampler.join();
  return peak.load();
}

// The training with a cache writes each parameter's states block by block as they are
// integrated (integrateInBlocks): a trajectory 4x as long costs the training no more heap. (Held
// whole until the parameter finished, the states were 401 and 1601 columns of 1024 doubles, 3.3
// and 13.1 MB on one rank: the longer run grew about 3x.) The 1.2 is the bound for the
// snapshot count.
TEST(Training, HoldsOneBlockOfStatesHoweverLongTheTrajectory) {
  auto comm = Tpetra::getDefaultComm();
  TempDir dir;
  const Nls1d scene(512);
  std::vector<double> growth;
  for (int steps : {400, 1600}) {
    TrainingOptions o = smallTraining();
    o.parameters = {{1.0}};
    o.steps = steps;
    o.snapshotEvery = 1;
    const ArtifactsCache cache(dir.file("t" + std::to_string(steps) + ".h5"), comm, scene.name(), 1024);
    TrainingResult t;
    growth.push_back(peakHeapGrowthOf([&] { t = runTraining(scene, comm, o, &cache, "key"); }));
    ASSERT_EQ(t.snapshots.numColumns(0), static_cast<size_t>(steps + 1));
  }
  std::printf("peak heap growth of the training: %.0f B (400 steps), %.0f B (1600 steps)\n", growth[0], growth[1]);
  EXPECT_LE(growth[1], 1.2 * growth[0]) << "peak heap growth " << growth[0] << " B (400 steps), " << growth[1]
                                        << " B (1600 steps)";
}

// Each stage's cache key holds what changes its results and follows the keys of the stages it
// depends on: a changed option changes its stage's key and those after it, nothing before; the
// group sizes and progress (who computes what, what is printed) change none.
TEST(OfflineSequence, EachStageKeysWhatChangesItsResults) {
  const Nls1d scene(32);
  OfflineOptions o;
  o.training = smallTraining();
  o.basis.k = 4;
  o.ms = {6};
  o.sceneConfig = "scene:\n  name: nls1d\n  n: 32\n";
  const OfflineKeys base = offlineKeys(scene, o);
  // which of training, basis, deim, nnls changed
  auto changed = [&](const OfflineOptions& x) {
    const OfflineKeys k = offlineKeys(scene, x);
    return std::vector<bool>{k.training != base.training, k.basis != base.basis, k.deim != base.deim, k.nnls != base.nnls};
  };
  using V = std::vector<bool>;
  OfflineOptions x = o;
  x.training.groupSize = 2, x.training.progress = true, x.deim.groupSize = 3;
  EXPECT_EQ(changed(x), (V{false, false, false, false}));
  x = o, x.training.dt = 0.02;
  EXPECT_EQ(changed(x), (V{true, true, true, true}));
  x = o, x.training.parameters.back() = {1.2};
  EXPECT_EQ(changed(x), (V{true, true, true, true}));
  x = o, x.sceneConfig = "scene:\n  name: nls1d\n  n: 64\n";
  EXPECT_EQ(changed(x), (V{true, true, true, true}));
  x = o, x.training.integrator.set("scheme", "imr");
  EXPECT_EQ(changed(x), (V{true, true, true, true}));
  x = o, x.basis.blockColumns = 64;
  EXPECT_EQ(changed(x), (V{false, true, true, true}));
  x = o, x.basis.podRoute = "tree";  // auto stays out of the key; another route is another basis
  EXPECT_EQ(changed(x), (V{false, true, true, true}));
  x = o, x.deim.svd = "randomized";
  EXPECT_EQ(changed(x), (V{false, false, true, false}));
  x = o, x.ms = {12};  // maxRank 0 keeps 12 + 32 triplets instead of 6 + 32
  EXPECT_EQ(changed(x), (V{false, false, true, false}));
  x = o, x.deim.maxRank = 50;
  const std::string fixed = offlineKeys(scene, x).deim;
  x.ms = {12};  // with maxRank given, the largest m no longer matters
  EXPECT_EQ(offlineKeys(scene, x).deim, fixed);
  x = o, x.eqp.seed = 7;
  EXPECT_EQ(changed(x), (V{false, false, false, true}));
  x = o, x.eqpTolerance = 1e-4;
  EXPECT_EQ(changed(x), (V{false, false, false, true}));
}

// The stages run in their one order whatever is asked first, each once; a second sequence on the
// same artifacts file takes them from it, bit for bit.
TEST(OfflineSequence, StagesInOrderOnceThenFromTheCache) {
  auto comm = Tpetra::getDefaultComm();
  TempDir dir;
  const Nls1d scene(32);
  OfflineOptions o;
  o.training = smallTraining();
  o.basis.k = 4;
  o.ms = {6};
  const ArtifactsCache cache(dir.file("a.h5"), comm, "nls1d", 64);
  auto run = [&](std::vector<OfflineStageEnd>& ends) {
    OfflineSequence seq(scene, comm, o, {1.0}, &cache);
    seq.setStageHook([&](const OfflineStageEnd& e) { ends.push_back(e); });
    auto U = rcp(new MultiVector(*seq.deimBasis(4).basis.U, Teuchos::Copy));  // asks for the stages before it
    seq.deimBasis(4);                                                          // held: no stage
    EXPECT_EQ(seq.sizes(), std::vector<int>{4});
    std::vector<std::string> clocks;
    for (const auto& s : seq.clocks().stages()) clocks.push_back(s.name);
    EXPECT_EQ(clocks, (std::vector<std::string>{"training", "instance", "basis", "deim basis k=4"}));
    return U;
  };
  std::vector<OfflineStageEnd> first, second;
  const auto U1 = run(first), U2 = run(second);
  ASSERT_EQ(first.size(), 4u);
  ASSERT_EQ(second.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(first[i].name, second[i].name);
    EXPECT_FALSE(first[i].cached) << first[i].name;
    EXPECT_EQ(second[i].cached, first[i].name != "instance") << second[i].name;
  }
  ASSERT_EQ(U1->getNumVectors(), U2->getNumVectors());
  for (size_t j = 0; j < U1->getNumVectors(); ++j) {
    const auto a = U1->getData(j), b = U2->getData(j);
    for (Teuchos::ArrayRCP<const double>::size_type i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]);
  }
}

TEST(ModelFileBuild, TheFileTheOnlineLibraryLoads) {
  auto comm = Tpetra::getDefaultComm();
  TempDir dir;
  const auto scene = std::make_shared<Nls1d>(32);
  // m = 200: past the DEIM basis (at most d = 32 vectors); gp-eqp stops at fewer terms
  ModelBuildOptions o = smallBuild(4, {6, 8, 200});
  o.methods = {"gp-deim", "gp-eqp"};
  o.file.probes = {3};
  o.file.interpolationNodes = 3;
  const ModelBuildResult r = buildReducedModelFile(*scene, comm, o, dir.file("m.h5"));
  EXPECT_EQ(r.basis.basis.k, 4);
  EXPECT_DOUBLE_EQ(r.data.T, 0.2);  // steps x dt when no horizon is given
  const ReducedModel file(dir.file("m.h5"), scene);
  EXPECT_EQ(file.data().sceneName, "nls1d");
  std::vector<std::string> held;
  for (const auto& m : file.data().models) held.push_back(m.method + " " + std::to_string(m.k) + " " + std::to_string(m.m));
  EXPECT_EQ(held, (std::vector<std::string>{"gp-deim 4 6", "gp-deim 4 8", "gp-eqp 4 6", "gp-eqp 4 8", "gp-eqp 4 200"}));
  // what could not be built is left out and named, the rest written (as gphr run marks it unavailable)
  ASSERT_EQ(r.skipped.size(), 1u);
  EXPECT_EQ(r.skipped[0].rfind("gp-deim k = 4, m = 200: the DEIM basis has ", 0), 0u) << r.skipped[0];
  // AVF conserves the model's H_hr to the Newton tolerance (1e-10 relative by default; 1e-8 leaves
  // room for 20 steps of it).
  auto online = file.instantiate("gp-deim", 4, 8, {1.0});
  double H0 = 0.0, drift = 0.0;
  const auto stats = online.simulate(0.2, 0.01, [&](const QueryStep& s) {
    if (s.step == 0) H0 = s.hamiltonian;
    drift = std::max(drift, std::abs(s.hamiltonian - H0));
  });
  EXPECT_TRUE(stats.ok());
  EXPECT_LE(drift, 1e-8 * std::abs(H0));
  ModelBuildOptions bad = o;
  bad.methods = {"deim"};  // a baseline: not storable
  EXPECT_THROW(buildReducedModelFile(*scene, comm, bad, dir.file("bad.h5")), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir.file("bad.h5")));
  bad = o, bad.ms = {200}, bad.methods = {"gp-deim"};  // nothing to store: an error, no file
  EXPECT_THROW(buildReducedModelFile(*scene, comm, bad, dir.file("bad.h5")), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir.file("bad.h5")));
}


TEST(GreedyTraining, StartsAtTheCornersAndCentreAndSeedsItsCandidates) {
  ParameterBox box;
  box.names = {"a", "b"};
  box.bounds = {{0.0, 1.0}, {2.0, 4.0}};
  EXPECT_EQ(cornersAndCentre(box),
            (std::vector<std::vector<double>>{{0, 2}, {1, 2}, {0, 4}, {1, 4}, {0.5, 3}}));
  EXPECT_EQ(greedyStart(box, "corners"), cornersAndCentre(box));
  EXPECT_EQ(greedyStart(box, "centre"), (std::vector<std::vector<double>>{{0.5, 3}}));
  EXPECT_THROW(greedyStart(box, "center"), InputError);
  const auto a = candidatePoints(box, 50, 7), b = candidatePoints(box, 50, 7), c = candidatePoints(box, 50, 8);
  EXPECT_EQ(a, b);  // the same seed, the same points
  EXPECT_NE(a, c);
  for (const auto& mu : a) {
    EXPECT_TRUE(mu[0] >= 0.0 && mu[0] < 1.0 && mu[1] >= 2.0 && mu[1] < 4.0);
  }
}

// Each round adds the candidate where the best model's estimate is largest: the first round's pick
// equals the worst candidate of a file built from the corners and centre alone, queried at every
// candidate; the file records the rounds; every rank picks the same points.
TEST(GreedyTraining, AddsTheWorstCandidateOfTheBestModel) {
  auto comm = Tpetra::getDefaultComm();
  TempDir dir;
  const auto scene = std::make_shared<Nls1d>(32);
  ModelBuildOptions o = smallBuild(3, {6});
  GreedyOptions g;
  g.targetError = 1e-9;  // not met: the build stops at maxPoints
  g.candidates = 6;
  g.seed = 3;
  g.maxPoints = 4;
  const GreedyResult r = buildToTargetError(*scene, comm, o, dir.file("g.h5"), g);
  EXPECT_FALSE(r.met);
  ASSERT_EQ(r.rounds.size(), 2u);  // 3 points (corners and centre of the eps box), then 4
  EXPECT_EQ(r.rounds[0].fullSolves, 3);
  EXPECT_EQ(r.rounds[1].fullSolves, 4);
  EXPECT_TRUE(r.rounds[1].added.empty());
  ASSERT_EQ(r.rounds[0].added.size(), 1u);
  // the pick, recomputed from a file of the first round's training set
  o.training.parameters = cornersAndCentre(scene->parameterBox());
  buildReducedModelFile(*scene, comm, o, dir.file("first.h5"));
  const ReducedModel first(dir.file("first.h5"), scene);
  double worst = -1.0;
  std::vector<double> at;
  for (const auto& mu : candidatePoints(scene->parameterBox(), g.candidates, g.seed)) {
    const double e = first.instantiate("gp-deim", 3, 6, mu).simulate(0.2, 0.01).errorEstimate;
    if (e > worst) worst = e, at = mu;
  }
  EXPECT_EQ(r.rounds[0].added, at);
  EXPECT_DOUBLE_EQ(r.rounds[0].maxEstimate, worst);
  // two points per round: the worst, then pointsToAdd's second, both in the training set
  GreedyOptions two = g;
  two.pointsPerRound = 2;
  two.maxPoints = 5;
  const GreedyResult r2 = buildToTargetError(*scene, comm, o, dir.file("g2.h5"), two);
  ASSERT_EQ(r2.rounds.size(), 2u);
  EXPECT_EQ(r2.rounds[1].fullSolves, 5);
  EXPECT_EQ(r2.rounds[0].added, at);
  const auto candidates = candidatePoints(scene->parameterBox(), g.candidates, g.seed);
  std::vector<double> estimates;
  for (const auto& mu : candidates) estimates.push_back(first.instantiate("gp-deim", 3, 6, mu).simulate(0.2, 0.01).errorEstimate);
  const auto picked = pointsToAdd(scene->parameterBox(), candidates, estimates, two.targetError, 2);
  ASSERT_EQ(picked.size(), 2u);
  ASSERT_EQ(r2.build.training.parameters.size(), 5u);
  EXPECT_EQ(r2.build.training.parameters[3], candidates[picked[0]]);
  EXPECT_EQ(r2.build.training.parameters[4], candidates[picked[1]]);
  // the file's record, read back
  const ReducedModel file(dir.file("g.h5"), scene);
  ASSERT_EQ(file.data().greedy.size(), 2u);
  EXPECT_EQ(file.data().greedy[0].added, at);
  EXPECT_EQ(file.data().greedy[1].fullSolves, 4);
  EXPECT_EQ(file.data().targetError, 1e-9);
  // refused before any work: a target that is not a relative error, and no model to estimate
  GreedyOptions bad = g;
  bad.targetError = 0.0;
  EXPECT_THROW(buildToTargetError(*scene, comm, o, dir.file("bad.h5"), bad), InputError);
  ModelBuildOptions adeimOnly = o;
  adeimOnly.methods = {"gp-adeim"};
  EXPECT_THROW(buildToTargetError(*scene, comm, adeimOnly, dir.file("bad.h5"), g), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir.file("bad.h5")));
  // the same pick on every rank
  double lo = at[0], hi = at[0];
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MIN, at[0], Teuchos::outArg(lo));
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, at[0], Teuchos::outArg(hi));
  EXPECT_EQ(lo, hi);
}

// A round's points: by estimate, the worst first, only those above the target, each at least
// 0.5 / ceil(count^(1/p)) from the others (the box scaled to the unit cube), at most `count`.
TEST(GreedyTraining, ARoundsPointsAreTheWorstSpreadApart) {
  ParameterBox box;
  box.names = {"a", "b"};
  box.bounds = {{0.0, 1.0}, {0.0, 10.0}};
  // radius for 4 points in 2 parameters: 0.5 / 2 = 0.25 of the unit square
  const std::vector<std::vector<double>> c = {{0.1, 1}, {0.15, 1.5}, {0.9, 9}, {0.5, 5}, {0.6, 5}, {0.3, 8}};
  const std::vector<double> e = {9, 8, 7, 6, 5, 1};
  EXPECT_EQ(pointsToAdd(box, c, e, 0.5, 4), (std::vector<size_t>{0, 2, 3, 5}));  // 1: beside 0; 4: beside 3
  EXPECT_EQ(pointsToAdd(box, c, e, 0.5, 2), (std::vector<size_t>{0, 2}));       // at most 2 (radius 0.5 / 2)
  EXPECT_EQ(pointsToAdd(box, c, e, 6.5, 4), (std::vector<size_t>{0, 2}));       // only those above the target
  EXPECT_EQ(pointsToAdd(box, c, e, 0.5, 1), (std::vector<size_t>{0}));          // one: the worst
  EXPECT_EQ(pointsToAdd(box, c, e, 100, 3), (std::vector<size_t>{0}));          // none above: the worst alone
  EXPECT_THROW(pointsToAdd(box, c, {1, 2}, 0.5, 2), InputError);
}

// The query defaults: per method the cheapest model (onlineCostProxy) whose largest estimate met
// the target, else the method's smallest estimate; a model without an estimate (gp-adeim) gives none.
TEST(GreedyTraining, QueryDefaultIsTheCheapestModelMeetingTheTarget) {
  EXPECT_EQ(onlineCostProxy(3, 8), 6.0 * 6 * 6 / 3 + 2 * 8 * 36);  // 72 + 576
  std::vector<StoredHyperModel> models(6);
  const std::vector<std::tuple<const char*, int, int>> sizes = {
      {"gp-deim", 3, 4}, {"gp-deim", 3, 8}, {"gp-deim", 5, 6}, {"gp-eqp", 3, 4}, {"gp-eqp", 3, 8}, {"gp-adeim", 3, 4}};
  for (size_t i = 0; i < models.size(); ++i)
    models[i].method = std::get<0>(sizes[i]), models[i].k = std::get<1>(sizes[i]), models[i].m = std::get<2>(sizes[i]);
  const std::map<std::string, double> largest = {{"gp-deim/k3/m4", 0.02}, {"gp-deim/k3/m8", 0.005},
                                                 {"gp-deim/k5/m6", 0.004}, {"gp-eqp/k3/m4", 0.5}, {"gp-eqp/k3/m8", 0.3}};
  const auto d = chooseQueryDefaults(models, largest, 0.01);
  ASSERT_EQ(d.size(), 2u);  // gp-deim, gp-eqp; none for gp-adeim
  EXPECT_EQ(d[0].method, "gp-deim");  // k = 3, m = 8 (cost 648) before k = 5, m = 6 (cost 1533); m = 4 misses
  EXPECT_EQ(std::make_pair(d[0].k, d[0].m), std::make_pair(3, 8));
  EXPECT_TRUE(d[0].met);
  EXPECT_EQ(d[0].estimatedMax, 0.005);
  EXPECT_EQ(d[1].method, "gp-eqp");  // none meets 0.01: the smallest estimate, marked not met
  EXPECT_EQ(std::make_pair(d[1].k, d[1].m), std::make_pair(3, 8));
  EXPECT_FALSE(d[1].met);
  EXPECT_TRUE(std::isnan(d[1].verifiedMax));
}

// A greedy training's target, candidates, seed and fresh points.
GreedyOptions greedyOptions(double target, int candidates, unsigned long seed, int confirmPoints) {
  GreedyOptions g;
  g.targetError = target;
  g.candidates = candidates;
  g.seed = seed;
  g.confirmPoints = confirmPoints;
  return g;
}

// A greedy build stores the defaults, confirmed by full solves at fresh points (neither candidates
// nor training points): the estimate recomputed from the file at every candidate, and an E_L2 there.
TEST(GreedyTraining, StoresConfirmedQueryDefaults) {
  auto comm = Tpetra::getDefaultComm();
  TempDir dir;
  const auto scene = std::make_shared<Nls1d>(32);
  ModelBuildOptions o = smallBuild(3, {4, 6});
  // target 0.5: met by both models in the first round: the cheaper one, m = 4, is the default
  const GreedyOptions g = greedyOptions(0.5, 5, 4, 2);
  const GreedyResult r = buildToTargetError(*scene, comm, o, dir.file("g.h5"), g);
  ASSERT_TRUE(r.met);
  const ReducedModel file(dir.file("g.h5"), scene);
  ASSERT_EQ(file.data().queryDefaults.size(), 1u);
  const QueryDefault& q = file.data().queryDefaults[0];
  EXPECT_EQ(q.method, "gp-deim");
  EXPECT_EQ(std::make_pair(q.k, q.m), std::make_pair(3, 4));
  EXPECT_TRUE(q.met);
  double largest = 0.0;
  for (const auto& mu : candidatePoints(scene->parameterBox(), g.candidates, g.seed))
    largest = std::max(largest, file.instantiate("gp-deim", 3, 4, mu).simulate(0.2, 0.01).errorEstimate);
  EXPECT_DOUBLE_EQ(q.estimatedMax, largest);
  // confirmed: a finite error of a model that works (E_L2 < 1), at points trained on by no one
  EXPECT_TRUE(std::isfinite(q.verifiedMax) && q.verifiedMax > 0.0 && q.verifiedMax < 1.0) << q.verifiedMax;
  const auto fresh = freshPoints(scene->parameterBox(), g.confirmPoints, g.seed);
  ASSERT_EQ(fresh.size(), 2u);
  for (const auto& mu : fresh) {
    EXPECT_EQ(std::count(file.data().trainingParameters.begin(), file.data().trainingParameters.end(), mu), 0);
    const auto c = candidatePoints(scene->parameterBox(), g.candidates, g.seed);
    EXPECT_EQ(std::count(c.begin(), c.end(), mu), 0);
  }
}

// A confirmation that contradicts the estimate: at this seed the one candidate's estimate reads
// 1.1e-5 and the E_L2 at the 6 fresh points reach 3.1e-5 (measured; smooth, non-chaotic figures), so
// a target of 1.8e-5, 1.7x from each, is met by the estimate and missed by the full solves: the
// fresh points join the training, the rounds go on, and the next confirmation
// takes the next 6 points of the fresh stream; with maxTrainingPoints 9 there is no room for a
// third, and the build stops there.
TEST(GreedyTraining, AConfirmationThatMissesTrainsItsPointsAndGoesOn) {
  auto comm = Tpetra::getDefaultComm();
  TempDir dir;
  const auto scene = std::make_shared<Nls1d>(32);
  ModelBuildOptions o = smallBuild(3, {4, 6});
  GreedyOptions g = greedyOptions(1.8e-5, 1, 3, 6);
  g.maxPoints = 9;
  const GreedyResult r = buildToTargetError(*scene, comm, o, dir.file("g.h5"), g);
  const auto& box = scene->parameterBox();
  const auto stream = freshPoints(box, 12, g.seed);
  const std::vector<std::vector<double>> first(stream.begin(), stream.begin() + 6), second(stream.begin() + 6, stream.end());
  EXPECT_EQ(first, freshPoints(box, 6, g.seed));  // the first confirmation's points: the stream's first 6
  ASSERT_EQ(r.rounds.size(), 2u);
  EXPECT_EQ(r.rounds[0].fullSolves, 3);
  EXPECT_LE(r.rounds[0].maxEstimate, g.targetError);  // met by the estimate ...
  EXPECT_EQ(r.rounds[0].added, first.front());        // ... and its confirmation's points added
  EXPECT_EQ(r.rounds[1].fullSolves, 9);
  std::vector<std::vector<double>> trained = cornersAndCentre(box);
  trained.insert(trained.end(), first.begin(), first.end());
  const ReducedModel file(dir.file("g.h5"), scene);
  EXPECT_EQ(file.data().trainingParameters, trained);
  ASSERT_EQ(file.data().queryDefaults.size(), 1u);
  // the default's verified figure is the second confirmation's: E_L2 at the next 6 points, none trained
  const QueryDefault& q = file.data().queryDefaults[0];
  for (const auto& mu : second) EXPECT_EQ(std::count(trained.begin(), trained.end(), mu), 0);
  EXPECT_TRUE(std::isfinite(q.verifiedMax) && q.verifiedMax > 0.0) << q.verifiedMax;
  EXPECT_EQ(file.data().greedy.size(), 2u);
  // the file's offline seconds count the whole training (three builds and two confirmations), not
  // only the last build's (which repeats no training: every stage from memory)
  EXPECT_GT(file.data().offlineSeconds, r.build.seconds);
  // without a confirmation the estimate's word is final: one round, nothing verified
  GreedyOptions unconfirmed = g;
  unconfirmed.confirmPoints = 0;
  const GreedyResult u = buildToTargetError(*scene, comm, o, dir.file("u.h5"), unconfirmed);
  EXPECT_TRUE(u.met);
  EXPECT_EQ(u.rounds.size(), 1u);
  ASSERT_EQ(u.build.data.queryDefaults.size(), 1u);
  EXPECT_TRUE(std::isnan(u.build.data.queryDefaults[0].verifiedMax));
}

}  // namespace
}  // namespace gphr
