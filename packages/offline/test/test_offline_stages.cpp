// The offline library on its own (no application): the training grid, the artifacts cache's
// rule (a dataset counts only with its key and its `complete` mark), a training resumed from the
// cache (bit-identical snapshots, unfinished parameters redone), and buildReducedModelFile's file
// loaded by the online library.
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>
#include <Teuchos_CommHelpers.hpp>
#include <filesystem>
#include <unistd.h>

#include "gphr/core/Error.hpp"
#include "gphr/models/Scene.hpp"
#include "gphr/offline/ModelFileBuild.hpp"
#include "gphr/online/ReducedModel.hpp"

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
    ArtifactsCache::seal(*f, "/stage/x", "key 1");
    EXPECT_TRUE(ArtifactsCache::holds(*f, "/stage/x", "key 1"));
    EXPECT_FALSE(ArtifactsCache::holds(*f, "/stage/x", "key 2"));
    EXPECT_FALSE(ArtifactsCache::holds(*f, "/stage/y", "key 1"));
  }
  EXPECT_NO_THROW(ArtifactsCache(dir.file("a.h5"), comm, "nls1d", 64));
  EXPECT_THROW(ArtifactsCache(dir.file("a.h5"), comm, "swe2d", 64), InputError);  // another scene
  EXPECT_THROW(ArtifactsCache(dir.file("a.h5"), comm, "nls1d", 80), InputError);  // another size
}

double maxDifference(const MultiVector& a, const MultiVector& b) {
  MultiVector d(a, Teuchos::Copy);
  d.update(-1.0, b, 1.0);
  std::vector<double> n(d.getNumVectors());
  d.normInf(n);
  return *std::max_element(n.begin(), n.end());
}

TEST(Training, ResumedFromTheCacheBitForBit) {
  auto comm = Tpetra::getDefaultComm();
  TempDir dir;
  const Nls1d scene(32);
  const ArtifactsCache cache(dir.file("a.h5"), comm, scene.name(), 64);
  const TrainingOptions o = smallTraining();
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

TEST(ModelFileBuild, TheFileTheOnlineLibraryLoads) {
  auto comm = Tpetra::getDefaultComm();
  TempDir dir;
  const auto scene = std::make_shared<Nls1d>(32);
  ModelBuildOptions o;
  o.training = smallTraining();
  o.basis.k = 4;
  o.ms = {6, 8};
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
  EXPECT_EQ(held, (std::vector<std::string>{"gp-deim 4 6", "gp-deim 4 8", "gp-eqp 4 6", "gp-eqp 4 8"}));
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
}

}  // namespace
}  // namespace gphr
