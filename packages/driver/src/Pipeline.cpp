#include "gphr/driver/Pipeline.hpp"

#include <Teuchos_Time.hpp>
#include <Teuchos_YamlParameterListCoreHelpers.hpp>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "gphr/core/Error.hpp"
#include "gphr/driver/Config.hpp"
#include "gphr/io/Hdf5File.hpp"
#include "gphr/driver/ModelEvaluation.hpp"
#include "gphr/reduction/GalerkinRom.hpp"
#include "gphr/timeint/DenseModelIntegrator.hpp"
#include "gphr/timeint/FullModelIntegrator.hpp"

namespace gphr {

// The config that determines the training snapshots: scene, time, integrator, training.
std::string trainingKey(const Teuchos::ParameterList& cfg) {
  Teuchos::ParameterList k("training-stage");
  for (const char* s : {"scene", "time", "integrator", "training"}) k.sublist(s) = cfg.sublist(s);
  return toYaml(k);
}

std::string basisKey(const Teuchos::ParameterList& cfg) {
  // podRoute's default (auto) is what every basis cached before the key existed was computed with
  // (then TSQR where it fit, now the stacked route: both exact SVDs, equal to round-off): it stays
  // out of the key, so those caches remain valid; another route is a different key.
  Teuchos::ParameterList red = cfg.sublist("reduction");
  if (red.isParameter("podRoute") && red.get<std::string>("podRoute") == "auto") red.remove("podRoute");
  return trainingKey(cfg) + toYaml(red) + "k = " + std::to_string(basisK(cfg));
}

namespace {

std::string datasetName(size_t j) { return "/training/p" + std::to_string(j); }

// Open the artifacts file for the training stage, or create it. Scene or size mismatch is an error.
std::unique_ptr<Hdf5File> openArtifacts(const RunContext& ctx, long fullDim, bool& fresh) {
  const std::string path = ctx.artifactsPath();
  fresh = !std::filesystem::exists(path);
  ctx.comm->barrier();
  if (fresh) {
    auto f = std::make_unique<Hdf5File>(path, ctx.comm, Hdf5File::Mode::Create);
    f->setAttribute("/", "scene", ctx.scene->name());
    f->setAttribute("/", "fullDim", std::vector<double>{double(fullDim)});
    return f;
  }
  auto f = std::make_unique<Hdf5File>(path, ctx.comm, Hdf5File::Mode::ReadWrite);
  const std::string scene = f->hasAttribute("/", "scene") ? f->stringAttribute("/", "scene") : "";
  GPHR_REQUIRE(scene == ctx.scene->name(), InputError, "artifacts file '", path, "' belongs to scene '", scene,
               "' but the config runs '", ctx.scene->name(), "' (use another --output directory)");
  if (f->hasAttribute("/", "fullDim")) {
    const double nd = f->doubleAttribute("/", "fullDim")[0];
    GPHR_REQUIRE(nd == fullDim, InputError, "artifacts file '", path, "' holds states of size ", nd,
                 " but the config gives size ", fullDim, " (use another --output directory)");
  } else {
    f->setAttribute("/", "fullDim", std::vector<double>{double(fullDim)});
  }
  return f;
}

class Progress {
 public:
  explicit Progress(bool root) : root_(root), clock_("train") { clock_.start(); }
  void done(size_t j, size_t total, size_t computed, const std::vector<double>& mu, bool reused) {
    if (!root_) return;
    const double el = clock_.totalElapsedTime(true);
    std::ostringstream m;
    for (double x : mu) m << (m.tellp() ? ", " : "") << x;
    std::fprintf(stderr, "[gphr] train: parameter %zu/%zu (%s) %s, %.1f s elapsed, ~%.1f s left\n", j + 1, total,
                 m.str().c_str(), reused ? "reused from file" : "done",
                 el, computed ? el / computed * (total - j - 1) : 0.0);
  }

 private:
  bool root_;
  Teuchos::Time clock_;
};

}  // namespace

TrainingResult runTraining(const RunContext& ctx) {
  Teuchos::Time clock("train");
  clock.start();
  TrainingResult res;
  res.parameters = trainingParameters(ctx.config);
  const long steps = numSteps(ctx.config), every = ctx.config.sublist("training").get<int>("snapshotEvery");
  const double dt = ctx.config.sublist("time").get<double>("dt");
  const std::string key = trainingKey(ctx.config);
  auto probe = ctx.scene->instantiate(ctx.comm, res.parameters[0], true);
  const PhaseSpace& ps = probe.system->space();
  bool fresh = false;
  {
    auto f = openArtifacts(ctx, ps.fullDim(), fresh);
    if (!f->exists("/training")) f->createGroup("/training");
    if (!f->hasAttribute("/training", "config") || f->stringAttribute("/training", "config") != key) {
      if (!fresh && f->hasAttribute("/training", "config") && ctx.comm->getRank() == 0)
        std::fprintf(stderr, "[gphr] train: the training config changed; training again\n");
      for (size_t j = 0; f->exists(datasetName(j)); ++j) f->remove(datasetName(j));
      f->remove("/basis");
      f->setAttribute("/training", "config", key);
    }
  }
  Progress progress(ctx.comm->getRank() == 0);
  size_t computed = 0;
  for (size_t j = 0; j < res.parameters.size(); ++j) {
    const auto& mu = res.parameters[j];
    {
      Hdf5File f(ctx.artifactsPath(), ctx.comm, Hdf5File::Mode::ReadWrite);
      if (f.hasAttribute(datasetName(j), "complete")) {
        res.snapshots.push_back(f.readStates(datasetName(j), ps));
        res.reused++;
        progress.done(j, res.parameters.size(), computed, mu, true);
        continue;
      }
      f.remove(datasetName(j));  // half-written by a killed run: redo
    }
    auto inst = ctx.scene->instantiate(ctx.comm, mu, true);
    FullModelIntegrator integ(inst.system, ctx.config.sublist("integrator"));
    auto snaps = rcp(new MultiVector(inst.system->map(), steps / every + 1));
    Vector y(*inst.y0, Teuchos::Copy);
    integ.run(y, dt, steps, [&](long s, double, const Vector& ys, const StepReport&) {
      if (s % every == 0) Tpetra::deep_copy(*snaps->getVectorNonConst(s / every), ys);
    });
    {
      // Written when the parameter has finished, file closed between parameters: a kill during
      // the next run leaves this one intact; the `complete` mark is the last thing written.
      Hdf5File f(ctx.artifactsPath(), ctx.comm, Hdf5File::Mode::ReadWrite);
      f.writeStates(datasetName(j), *snaps, ps);
      f.setAttribute(datasetName(j), "parameters", mu);
      f.setAttribute(datasetName(j), "config", key);
      f.flush();
      f.setAttribute(datasetName(j), "complete", std::string("yes"));
    }
    res.snapshots.push_back(snaps);
    ++computed;
    progress.done(j, res.parameters.size(), computed, mu, false);
  }
  res.seconds = clock.stop();
  return res;
}

int basisK(const Teuchos::ParameterList& cfg) {
  const auto ks = pipelineK(cfg);
  return std::max(cfg.sublist("reduction").get<int>("k"), *std::max_element(ks.begin(), ks.end()));
}

ReducedBasis runReduction(const RunContext& ctx, const TrainingResult& training, bool& cached) {
  const auto& red = ctx.config.sublist("reduction");
  const std::string key = basisKey(ctx.config);
  auto probe = ctx.scene->instantiate(ctx.comm, training.parameters[0], true);
  const PhaseSpace& ps = probe.system->space();
  Hdf5File f(ctx.artifactsPath(), ctx.comm, Hdf5File::Mode::ReadWrite);
  cached = f.hasAttribute("/basis", "config") && f.stringAttribute("/basis", "config") == key;
  ReducedBasis b;
  if (cached) {
    b.A = f.readStates("/basis", ps);
    // stored as rows: (2k, 2n) -> a MultiVector with 2k columns
    b.k = static_cast<int>(b.A->getNumVectors()) / 2;
    b.method = f.stringAttribute("/basis", "method");
    b.singularValues = f.doubleAttribute("/basis", "singularValues");
    b.energyCaptured = f.doubleAttribute("/basis", "energyCaptured")[0];
    const int wantK = basisK(ctx.config);
    GPHR_REQUIRE(wantK == 0 || wantK == b.k, InputError, "basis in '", ctx.artifactsPath(), "' has k = ", b.k,
                 " but the config asks for k = ", wantK);
    return b;
  }
  BasisOptions opt;
  opt.method = red.get<std::string>("method");
  opt.k = basisK(ctx.config);
  opt.energyTolerance = red.get<double>("energyTolerance");
  opt.blockColumns = red.get<int>("blockColumns");
  opt.maxRank = red.get<int>("maxRank");
  opt.podRoute = red.get<std::string>("podRoute");
  b = computeSymplecticBasis(training.snapshots, ps, opt);
  f.remove("/basis");
  f.writeStates("/basis", *b.A, ps);
  f.setAttribute("/basis", "method", b.method);
  f.setAttribute("/basis", "k", std::vector<double>{double(b.k)});
  f.setAttribute("/basis", "singularValues", b.singularValues);
  f.setAttribute("/basis", "energyCaptured", std::vector<double>{b.energyCaptured});
  f.setAttribute("/basis", "scene", ctx.scene->name());
  f.setAttribute("/basis", "trainingSet", [&] {
    std::vector<double> flat;
    for (const auto& mu : training.parameters) flat.insert(flat.end(), mu.begin(), mu.end());
    return flat;
  }());
  f.setAttribute("/basis", "layout", std::string("rows are the 2k columns of A (2n entries each, global-id order)"));
  f.setAttribute("/basis", "config", key);
  return b;
}

void setBasisKeys(const RunContext& ctx, const RomStages& st, JsonObject& run) {
  run.set("t_training_s", st.training.seconds)
      .set("t_basis_s", st.basisSeconds)
      .set("t_basis_cpu_s", st.basisCpuSeconds)
      .set("pod_route", ctx.config.sublist("reduction").get<std::string>("podRoute"))
      .set("pod_steps_tsqr", static_cast<long>(st.basis.tsqrSteps))
      .set("pod_steps_replicated", static_cast<long>(st.basis.replicatedSteps))
      .set("pod_steps_stacked", static_cast<long>(st.basis.stackedSteps));
}

void runRom(const RunContext& ctx, const FomResult& fom, RomStages& st) {
  auto inst = ctx.scene->instantiate(ctx.comm, ctx.mu, true);
  for (int k : stageK(ctx.config, st.basis)) {
    auto A = leadingBasis(st.basis, k);
    GalerkinRom rom(inst.system, A);
    ModelRun run = evaluateReducedModel(ctx.comm, evaluationSettingsFrom(ctx.config), fom, *inst.system, *A, rom, true, "rom", k, 0);
    run.run.set("basis", st.basis.method)
        .set("energy_captured", st.basis.energyCaptured)
        .set("training_parameters", static_cast<long>(st.training.parameters.size()))
        .set("training_reused", st.training.reused)
        .set("basis_cached", st.basisCached)
        .set("t_offline_s", st.training.seconds + st.basisSeconds);
    setBasisKeys(ctx, st, run.run);
    st.runs.push_back(std::move(run));
  }
}

}  // namespace gphr
