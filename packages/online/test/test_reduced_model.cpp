// The reduced-model file round trip: a model written by the builder and loaded by ReducedModel
// reproduces the model built in-process (as `gphr run` builds it) step by step; the exact set-up
// route reproduces it at any parameter, the interpolated one to its measured interpolation error;
// bad files and bad queries are refused with a message naming what is wrong.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <hdf5.h>

#include "HyperTestUtils.hpp"
#include "gphr/core/BlasThreads.hpp"
#include "gphr/core/Provenance.hpp"
#include "gphr/offline/ModelFileBuilder.hpp"
#include "gphr/online/ReducedModel.hpp"

using namespace gphr;
using namespace gphr::test;

namespace {

// A file name shared by all ranks (the write is collective).
std::string sharedPath(const std::string& name) {
  long pid = getpid();
  Teuchos::broadcast(*comm(), 0, Teuchos::outArg(pid));
  return "/tmp/gphr-test-rm-" + std::to_string(pid) + "-" + name + ".h5";
}

std::string integratorYaml(const std::string& scheme) {
  auto pl = denseIntegrator(scheme);
  return toYaml(pl);
}

void writeFile(const HyperCase& hc, const Scene& scene, int k, const std::vector<int>& ms, const std::string& scheme,
               bool withBasis, const std::string& path, double T, double dt) {
  ModelFileOptions opt;
  opt.integratorConfig = integratorYaml(scheme);
  opt.probes = {0, 3};
  ReducedModelData data = modelFileHeader(scene, hc.test, opt);
  data.T = T, data.dt = dt;
  addReducedBasis(data, scene, hc.test, *hc.basis.A, k, *hc.deim.U, ms, opt);
  const RCP<const MultiVector> A = withBasis ? RCP<const MultiVector>(hc.basis.A) : Teuchos::null;
  writeReducedModelFile(path, comm(), data, {A}, &hc.test.system->space());
}

std::vector<DenseVector> queried(OnlineModel& online, double T, double dt, std::vector<double>* H = nullptr,
                                 std::vector<std::vector<double>>* probes = nullptr) {
  std::vector<DenseVector> out;
  const auto stats = online.simulate(T, dt, [&](const QueryStep& s) {
    out.push_back(s.z);
    if (H) H->push_back(s.hamiltonian);
    if (probes) probes->push_back(s.probes);
  });
  EXPECT_TRUE(stats.ok()) << statusName(stats.status) << ": " << stats.reason;
  return out;
}

const double kDt = 0.05;
const long kSteps = 40;

}  // namespace

TEST(ReducedModelFile, RoundTripReproducesTheInProcessModel) {
  auto scene = std::make_shared<Nls1d>(64, 5.0);
  const auto hc = nlsCase(64, 4, comm());
  const std::string path = sharedPath("nls");
  writeFile(hc, *scene, 4, {6, 8}, "avf", false, path, kDt * kSteps, kDt);
  const ReducedModel rm(path, scene);
  EXPECT_EQ(rm.data().models.size(), 2u);
  // eps enters only the row kernel: L_r, f_r and y0 are stored once, c over eps's nodes.
  EXPECT_EQ(rm.data().basis(4).interpolant.numNodes(), 1u);
  EXPECT_EQ(rm.data().basis(4).constant.numNodes(), 7u);
  // At the test parameter (eps = 1.0, between interpolation nodes) and at another one: the NLS
  // parameter enters only the row kernel and c (affine in eps), which the interpolant reproduces
  // to round-off, so both trajectories agree with the in-process models to round-off. 1e-12 is
  // the bound asserted; measured below 1e-14.
  for (double eps : {1.0, 0.93}) {
    auto inst = scene->instantiate(comm(), {eps}, true);
    auto inRun = buildGpDeimModel(*inst.system, *hc.basis.A, *hc.deim.U, 8);
    const auto ref = trajectory(*inRun, "avf", kDt, kSteps);
    auto online = rm.instantiate("gp-deim", 4, 8, {eps});
    std::vector<double> H;
    const auto got = queried(online, kDt * kSteps, kDt, &H);
    ASSERT_EQ(got.size(), ref.size());
    const double diff = maxRelDiff(got, ref);
    std::printf("eps = %.2f: query against in-process model, max relative difference %.2e\n", eps, diff);
    EXPECT_LT(diff, 1e-12);
    // H_hr of the loaded model equals the in-process model's at each step (1e-12 relative: the
    // interpolated c carries a few ulps).
    for (size_t j = 0; j < H.size(); j += 10)
      EXPECT_NEAR(H[j], inRun->hamiltonian(got[j]), 1e-12 * (1 + std::abs(H[j])));
    EXPECT_FALSE(online.extrapolated());
  }
  if (comm()->getRank() == 0) std::remove(path.c_str());
}

// A query runs OpenBLAS on one thread whatever the caller set (core/BlasThreads.hpp), and gives it
// back after: so its bits do not depend on OPENBLAS_NUM_THREADS, as `gphr query`'s do not.
TEST(ReducedModelFile, AQueryRunsOpenBlasOnOneThreadAndGivesItBack) {
  if (blasThreads() == 0) GTEST_SKIP() << "the BLAS is not OpenBLAS";
  auto scene = std::make_shared<Nls1d>(64, 5.0);
  const auto hc = nlsCase(64, 4, comm());
  const std::string path = sharedPath("blas");
  writeFile(hc, *scene, 4, {8}, "avf", false, path, kDt * 10, kDt);
  const ReducedModel rm(path, scene);
  std::vector<std::vector<DenseVector>> runs;
  for (int threads : {2, 1}) {
    setBlasThreads(threads);
    ASSERT_EQ(blasThreads(), threads);  // the setter took: the check below can fail
    auto online = rm.instantiate("gp-deim", 4, 8, {1.0});
    std::vector<int> inside;
    std::vector<DenseVector> z;
    online.simulate(kDt * 10, kDt, [&](const QueryStep& s) {
      inside.push_back(blasThreads());
      z.push_back(s.z);
    });
    EXPECT_EQ(inside, std::vector<int>(11, 1)) << "OpenBLAS threads during the query, set " << threads;
    EXPECT_EQ(blasThreads(), threads);  // restored
    runs.push_back(z);
  }
  ASSERT_EQ(runs[0].size(), runs[1].size());
  for (size_t j = 0; j < runs[0].size(); ++j)
    for (int i = 0; i < runs[0][j].length(); ++i) ASSERT_EQ(runs[0][j](i), runs[1][j](i)) << "step " << j;
  comm()->barrier();  // the queries are not collective: no rank may still be reading the file
  if (comm()->getRank() == 0) std::remove(path.c_str());
}

TEST(ReducedModelFile, ProbesAreTheLiftedStateAtTheirEntries) {
  auto scene = std::make_shared<Nls1d>(64, 5.0);
  const auto hc = nlsCase(64, 4, comm());
  const std::string path = sharedPath("probes");
  writeFile(hc, *scene, 4, {8}, "avf", true, path, kDt * 4, kDt);
  const ReducedModel rm(path, scene);
  auto online = rm.instantiate("gp-deim", 4, 8, {1.0});
  std::vector<std::vector<double>> probes;
  const auto z = queried(online, kDt * 4, kDt, nullptr, &probes);
  // Reference: y0 + A z^j lifted with the full basis, read at entries 0 and 3.
  const auto y0 = gatherRows(*hc.test.system->reference(), {0, 3});
  const auto Arows = gatherRows(*hc.basis.A, {0, 3});
  for (size_t j = 0; j < z.size(); ++j)
    for (int p = 0; p < 2; ++p) {
      double y = y0[p];
      for (int c = 0; c < 8; ++c) y += Arows[p * 8 + c] * z[j](c);
      EXPECT_NEAR(probes[j][p], y, 1e-13 * (1 + std::abs(y)));  // the same sum, up to the order of terms
    }
  if (comm()->getRank() == 0) std::remove(path.c_str());
}

TEST(ReducedModelFile, SweExactRouteReproducesAndInterpolatedRouteIsClose) {
  auto scene = std::make_shared<Swe2d>(12);
  const auto hc = sceneCase(*scene, {{1.2, 0.8}, {1.6, 1.2}}, {1.4, 1.0}, 4, 0.01, 60, comm());
  const std::string path = sharedPath("swe");
  writeFile(hc, *scene, 4, {12}, "imr", true, path, 0.5, 0.01);
  const ReducedModel rm(path, scene);
  const auto& err = rm.data().basis(4).interpolationError;
  EXPECT_EQ(rm.data().basis(4).interpolant.numNodes(), 49u);  // beta and gamma both change L_r, f_r or y0
  std::printf("SWE interpolant (7 x 7 nodes), relative error between nodes: L %.1e f %.1e c %.1e reference %.1e\n",
              err.at("L"), err.at("f"), err.at("c"), err.at("reference"));
  const std::vector<double> mu{1.537, 0.912};  // no node: beta's Gaussian width enters the reference rows
  auto inst = scene->instantiate(comm(), mu, true);
  auto inRun = buildGpDeimModel(*inst.system, *hc.basis.A, *hc.deim.U, 12);
  const auto ref = trajectory(*inRun, "imr", 0.01, 50, 3);
  auto exact = rm.instantiate("gp-deim", 4, 12, mu, false, SetupRoute::Exact);
  const double dExact = maxRelDiff(queried(exact, 0.5, 0.01), ref);
  auto interp = rm.instantiate("gp-deim", 4, 12, mu);
  const double dInterp = maxRelDiff(queried(interp, 0.5, 0.01), ref);
  std::printf("SWE query against in-process model: exact route %.2e, interpolated route %.2e\n", dExact, dInterp);
  EXPECT_LT(dExact, 1e-12);  // the same projection: round-off only
  // The interpolated route differs by the interpolant's error (about 1e-8 on these pieces) times
  // the model's sensitivity over 50 steps; 1e-6 leaves room and still fails a wrong parameter map
  // (reference rows of another beta differ by ~1e-2).
  EXPECT_LT(dInterp, 1e-6);
  EXPECT_GT(dInterp, 0.0);  // it is a different route, not the exact one in disguise
  // c = H(y0(mu)) at each of its 49 nodes, which the build takes from the instances of the first
  // interpolant's nodes (the same points here): bit for bit the scene's own constant at that node,
  // since the same instance is computed the same way.
  const auto& constant = rm.data().basis(4).constant;
  ASSERT_EQ(constant.numNodes(), 49u);
  for (size_t j = 0; j < constant.numNodes(); ++j)
    EXPECT_EQ(constant.values()[j], scene->instantiate(comm(), constant.node(j), true).system->constant()) << "node " << j;
  if (comm()->getRank() == 0) std::remove(path.c_str());
}

TEST(ReducedModelFile, RefusesBadFilesAndQueries) {
  auto scene = std::make_shared<Nls1d>(64, 5.0);
  const auto hc = nlsCase(64, 4, comm());
  const std::string path = sharedPath("bad");
  writeFile(hc, *scene, 4, {8}, "avf", false, path, 1.0, kDt);
  auto refuses = [](const std::function<void()>& f, const std::string& words) {
    try {
      f();
      ADD_FAILURE() << "no error; expected one naming: " << words;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  const ReducedModel rm(path, scene);
  refuses([&] { rm.instantiate("gp-deim", 4, 9, {1.0}); }, "it holds gp-deim k=4 m=8");
  refuses([&] { rm.instantiate("gp-deim", 5, 8, {1.0}); }, "not in the reduced-model file");
  refuses([&] { rm.instantiate("gp-deim", 4, 8, {1.2}); }, "outside the training box (eps in [0.9, 1.1])");
  refuses([&] { rm.instantiate("gp-deim", 4, 8, {1.0, 2.0}); }, "takes 1 parameter(s)");
  refuses([&] { rm.instantiate("gp-deim", 4, 8, {1.0}, false, SetupRoute::Exact); }, "needs the basis");
  EXPECT_TRUE(rm.instantiate("gp-deim", 4, 8, {1.2}, true).extrapolated());
  refuses([&] { ReducedModel(path, std::make_shared<Swe2d>(8)); }, "is of scene 'nls1d'");
  comm()->barrier();
  if (comm()->getRank() == 0) {
    const std::string other = path + ".schema.h5", cut = path + ".cut.h5", junk = path + ".junk.h5";
    {  // another schema version
      std::ifstream in(path, std::ios::binary);
      std::ofstream(other, std::ios::binary) << in.rdbuf();
      const hid_t f = H5Fopen(other.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
      const hid_t a = H5Aopen(f, "schema_version", H5P_DEFAULT);
      const double v = 99;
      H5Awrite(a, H5T_NATIVE_DOUBLE, &v);
      H5Aclose(a);
      H5Fclose(f);
    }
    refuses([&] { ReducedModel(other, scene); }, "schema version 99");
    {  // truncated to half its size
      std::ifstream in(path, std::ios::binary);
      std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
      std::ofstream(junk, std::ios::binary) << std::string(4096, 'x');
    }
    refuses([&] { ReducedModel(cut, scene); }, "reduced-model file '" + cut + "'");
    refuses([&] { ReducedModel(junk, scene); }, "not an HDF5 file");
    refuses([&] { ReducedModel(path + ".missing", scene); }, "missing");
    for (const auto& p : {path, other, cut, junk}) std::remove(p.c_str());
  }
}

// What a file stores beside its numbers is checked when it is loaded, not when a query first uses
// it: the integrator and adeim sections through the config's validators and the bounds of a
// user's YAML, and the sample meshes' stencil widths against the scene's row kernel. Each file
// here is written by writeReducedModelFile, so its checksum is recomputed over the damage (as a
// hostile user can do): the checksum alone would pass every one of them.
TEST(ReducedModelFile, StoredSectionsAndStencilWidthsAreCheckedAtLoad) {
  auto scene = std::make_shared<Nls1d>(64, 5.0);
  const auto hc = nlsCase(64, 4, comm());
  ModelFileOptions opt;
  opt.integratorConfig = integratorYaml("avf");
  ReducedModelData good = modelFileHeader(*scene, hc.test, opt);
  good.T = 1.0, good.dt = kDt;
  addReducedBasis(good, *scene, hc.test, *hc.basis.A, 4, *hc.deim.U, {8}, opt);
  StoredHyperModel adaptive;
  adaptive.method = "gp-adeim", adaptive.k = 4, adaptive.m = 8;
  adaptive.adeimConfig = "adeim:\n  window: 2\n  initialWindow: 5\n";
  good.models.push_back(adaptive);
  const std::string path = sharedPath("sections");
  auto refusedAtLoad = [&](const ReducedModelData& d, const std::string& words) {
    writeReducedModelFile(path, comm(), d, {Teuchos::null});
    const auto start = std::chrono::steady_clock::now();
    try {
      ReducedModel rm(path, scene);
      ADD_FAILURE() << "loaded; expected an error naming: " << words;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(words), std::string::npos) << what;
      EXPECT_EQ(what.rfind("reduced-model file '" + path + "'", 0), 0u) << what;  // names the file first
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;                     // one line
      EXPECT_LT(what.size(), 600u) << what;  // no value repeated whole
    }
    // A bound, not a timing: 3,000 nesting levels took 27.7 s before the limits.
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0) << words;
  };
  {  // the good file loads, and its adeim options are the stored ones
    writeReducedModelFile(path, comm(), good, {Teuchos::null});
    EXPECT_NO_THROW(ReducedModel(path, scene));
  }
  ReducedModelData d = good;
  d.integratorConfig = "integrator:\n  newtonTolerance: -1.0\n";
  refusedAtLoad(d, "newtonTolerance");
  d.integratorConfig = "integrator:\n  newtonTolerence: 1.0e-10\n";
  refusedAtLoad(d, "newtonTolerence");
  d.integratorConfig.clear();  // nesting bomb: 3,000 flow levels on one line
  d.integratorConfig = "integrator:\n  scheme: " + std::string(3000, '[') + std::string(3000, ']') + "\n";
  refusedAtLoad(d, "nests");
  d.integratorConfig = "integrator:\n  scheme: '" + std::string(2 << 20, 'x') + "'\n";  // a 2 MB value
  refusedAtLoad(d, "allowed: at most");
  d.integratorConfig = "integrator:\n  scheme: [avf\n";
  refusedAtLoad(d, "its integrator section is malformed YAML");
  d = good;
  d.models.back().adeimConfig = "adeim:\n  window: 0\n";
  refusedAtLoad(d, "gp-adeim/k4/m8 adeim section");
  d = good;
  {  // row 0's stencil one entry wider (an entry of row 1's, which has a reference value): the
     // file stays consistent with itself, but the row kernel reads a fixed number per row
    RowSample& s = d.models.front().sample;
    const size_t r = static_cast<size_t>(s.reducedDim), e0 = s.stencil.offsets[1], extra = s.stencil.offsets[1];
    s.stencil.gids.insert(s.stencil.gids.begin() + e0, s.stencil.gids[extra]);
    s.basisRows.insert(s.basisRows.begin() + e0 * r, s.basisRows.begin() + extra * r,
                       s.basisRows.begin() + (extra + 1) * r);
    for (size_t i = 1; i < s.stencil.offsets.size(); ++i) ++s.stencil.offsets[i];
  }
  refusedAtLoad(d, "stencil entries; allowed: 2");
  d = good;  // numbers out of their range, checksum recomputed: refused by the checks, not the checksum
  d.models.front().sample.weights[1] = std::nan("");
  refusedAtLoad(d, "/weights has entry 1 = nan; allowed: finite numbers");
  d = good;
  d.models.front().sample.rows[1] = d.models.front().sample.rows[0];
  refusedAtLoad(d, "/rows names a term twice");
  comm()->barrier();
  if (comm()->getRank() == 0) std::remove(path.c_str());
}
