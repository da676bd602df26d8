// `gphr build CONFIG --model FILE.h5`: the offline phase (packages/offline, buildReducedModelFile)
// as the config sets it, reusing DIR/artifacts.h5 with `gphr run`: training, basis, DEIM basis
// and term-weight fits for every k and m of the pipeline, then the reduced-model file: per k the
// parameter interpolant of L_r, f_r, c and the reference rows (doc/model-file.md), per stored
// (method, k, m) its sample mesh. The full model is not evaluated. DIR/stages.csv: every rank's
// clocks per stage; DIR/mpi_calls.csv: their MPI time per MPI function (StageTable.hpp).
#include <algorithm>
#include <filesystem>
#include <memory>

#include "gphr/core/Error.hpp"
#include "gphr/core/Progress.hpp"
#include "gphr/driver/BuildCommand.hpp"
#include "gphr/driver/OutputDirectory.hpp"
#include "gphr/driver/Config.hpp"
#include "gphr/driver/OfflineStages.hpp"
#include "gphr/driver/OutputLock.hpp"
#include "gphr/offline/ModelFileBuild.hpp"
#include "gphr/driver/StageTable.hpp"
#include "gphr/core/Method.hpp"
#include "gphr/driver/GreedyReport.hpp"

namespace gphr {

namespace {

// The offline phase as the config sets it: the stored methods of pipeline.methods, k and m.
ModelBuildOptions buildOptions(const RunOptions& opt, const std::vector<std::string>& stored) {
  ModelBuildOptions o;
  static_cast<OfflineOptions&>(o) = opt.offline;
  o.methods = stored;
  o.adeim = opt.adeim;
  o.withBasis = opt.withBasis;
  o.file = opt.file;
  o.parameter = opt.mu;
  o.T = opt.T;
  o.config = opt.record.fullYaml;
  return o;
}

// Per model, its error indicator's calibration on the training parameters: the largest error
// there, measured and estimated, against the target where one is set.
void printCalibration(const ModelBuildResult& r) {
  const double target = r.data.targetError;
  for (const auto& x : r.data.models) {
    const auto it = r.calibration.find(x.key());
    if (it == r.calibration.end() || !x.calibration.calibrated()) {
      std::printf("  %s: no error estimate (%s)\n", x.key().c_str(),
                  it == r.calibration.end() ? "no indicator rows: build.indicatorDofs is 0"
                                            : "no training parameter gave both an error and an indicator");
      continue;
    }
    double measured = 0.0, estimated = 0.0;
    for (const auto& p : it->second)
      measured = std::max(measured, p.error), estimated = std::max(estimated, x.calibration.estimate(p.indicator));
    std::printf("  %s: error estimate = %.3g eta^%.2f, fitted on %d training parameters (within %.2fx of E_L2 there); "
                "largest E_L2 there %.2e, estimated %.2e%s\n", x.key().c_str(), x.calibration.scale,
                x.calibration.exponent, x.calibration.points, x.calibration.worstFactor, measured, estimated,
                target > 0.0 ? (estimated <= target ? ": meets the target error" : ": above the target error") : "");
  }
  if (target > 0.0)
    std::printf("  target error %.2e: queries whose estimate exceeds it are marked over_target\n", target);
}

// The greedy training's rounds: full solves, the best model's largest estimate, the point added.
void printGreedy(const GreedyResult& g, double target) {
  if (g.rounds.empty()) return;
  std::printf("  greedy training to %.2e: %s after %ld full solves (%zu rounds)\n", target,
              g.met ? "met" : "NOT met", g.rounds.back().fullSolves, g.rounds.size());
  for (const auto& r : g.rounds) {
    std::printf("    %3ld full solves: %s, largest estimate %.3e", r.fullSolves, r.model.c_str(), r.maxEstimate);
    for (size_t i = 0; i < r.added.size(); ++i) std::printf("%s%.6g", i ? ", " : "; adds (", r.added[i]);
    std::printf("%s\n", r.added.empty() ? "" : ")");
  }
  for (const auto& q : g.build.data.queryDefaults)
    std::printf("  query default of %s: k = %d, m = %d (estimated max %.3g%s; E_L2 max %.3g at fresh points)\n",
                q.method.c_str(), q.k, q.m, q.estimatedMax, q.met ? "" : ", target NOT met", q.verifiedMax);
}

void printBuild(const std::string& path, const ReducedModelData& data, double seconds, int ranks) {
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  std::printf("gphr build: %s (%.1f kB): %s; scene %s, offline %.1f s on %d rank(s)\n", path.c_str(), bytes / 1024.0,
              data.modelList().c_str(), data.sceneName.c_str(), seconds, ranks);
  for (const auto& b : data.bases)
    std::printf("  k = %d: parameter interpolants of %zu and %zu nodes, relative error between nodes: L_r %.1e, "
                "f_r %.1e, c %.1e, reference rows %.1e\n", b.k, b.interpolant.numNodes(), b.constant.numNodes(),
                b.interpolationError.at("L"),
                b.interpolationError.at("f"), b.interpolationError.at("c"), b.interpolationError.at("reference"));
}

}  // namespace

namespace {

// The model file replaces what is at --model (written beside it, then renamed over it): refuse,
// before any work, a path whose replacement would destroy something that is not a model file.
void checkModelPath(const std::string& modelPath, const std::string& configPath, const std::string& artifactsDir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(modelPath, ec);
  if (st.type() != fs::file_type::not_found) {
    const char* kind = st.type() == fs::file_type::directory ? "a directory"
                       : st.type() == fs::file_type::symlink ? "a symbolic link (give its target)"
                       : st.type() == fs::file_type::regular ? nullptr
                                                               : "not a regular file (a device, FIFO or socket)";
    GPHR_REQUIRE(kind == nullptr, InputError, "--model '", modelPath, "' is ", kind,
                 "; allowed: a new path or a regular file to replace");
  }
  // One spelling per file: "a/../a/x.h5" and "./a/x.h5" (lexically), links in the existing part.
  auto resolved = [&ec](const std::string& p) { return fs::weakly_canonical(fs::absolute(p).lexically_normal(), ec); };
  const fs::path model = resolved(modelPath);
  for (const auto& [other, what] : {std::pair<std::string, const char*>{configPath, "the config file"},
                                    {artifactsDir + "/artifacts.h5", "the artifacts file of --output"}})
    GPHR_REQUIRE(model != resolved(other), InputError, "--model '", modelPath, "' is ", what, "; allowed: another path");
}

}  // namespace

int runBuild(const std::string& configPath, const std::string& modelPath, const std::string& artifactsDir,
             const RCP<const Comm>& comm, double targetError) {
  // The command's own set-up (config, output directory, the scene's instance for the cache) is a
  // stage too: on a large scene its instance is not free.
  requireOutputsApart({{configPath, "the config file"}}, {{modelPath, "--model"}, {artifactsDir, "--output"}});
  StageClocks setup;
  auto setupClock = std::make_unique<StageClocks::Scope>(setup, "setup");
  RunOptions opt = runOptionsFrom(loadConfig(configPath));
  ProgressWatch::configure(opt.output.progressSeconds, comm->getRank() == 0);
  GPHR_REQUIRE(std::isfinite(targetError) && targetError >= 0.0 && targetError < 1.0, InputError, "--target-error ",
               targetError, "; allowed: 0 < EPS < 1 (a relative error E_L2)");
  if (targetError > 0.0) opt.greedy.targetError = opt.file.targetError = targetError;
  checkModelPath(modelPath, configPath, artifactsDir);
  RunContext ctx;
  ctx.comm = comm;
  ctx.outputDir = artifactsDir;
  std::vector<std::string> stored, skipped;
  for (const auto& m : opt.pipeline.methods) (methodInfo(m).storable ? stored : skipped).push_back(m);
  GPHR_REQUIRE(!stored.empty(), InputError, "config file '", configPath,
               "': gphr build stores ", methodNames([](const MethodInfo& m) { return m.storable; }),
               " models; pipeline.methods must list one of them");
  GPHR_REQUIRE(opt.evaluation.shift, InputError, "config file '", configPath,
               "': gphr build needs scene.shift: true (the stored models are of the shifted system)");
  const ModelBuildOptions options = buildOptions(opt, stored);
  const auto inst = opt.scene->instantiate(comm, opt.mu, true);
  checkModelBuildOptions(*opt.scene, options, inst.system->space().fullDim());  // before any file is made
  requireWritableBeside(modelPath, "--model", comm);  // not found after the offline run
  prepareOutputDir(ctx, false);
  const OutputLock lock(artifactsDir, "build", comm);
  const auto parent = std::filesystem::path(modelPath).parent_path();
  if (!parent.empty()) makeDirectory(parent.string(), comm);
  if (comm->getRank() == 0)  // the default --output is easy to miss: say where the cache goes
    std::fprintf(stderr, "[gphr] build: model file %s; artifacts cache and stage tables in %s\n", modelPath.c_str(),
                 artifactsDir.c_str());
  if (comm->getRank() == 0)
    for (const auto& m : skipped)
      std::fprintf(stderr, "[gphr] build: %s is not stored (%s)\n", m.c_str(),
                   "its online model needs all d rows or is a baseline: run it with gphr run");
  const ArtifactsCache cache = artifactsCache(ctx, opt, inst.system->space().fullDim());
  setupClock.reset();
  GreedyResult greedy;
  if (opt.greedy.targetError > 0.0 && comm->getRank() == 0)
    std::fprintf(stderr, "[gphr] build: greedy training to the target error %g (training.points and values not used)\n",
                 opt.greedy.targetError);
  if (opt.greedy.targetError > 0.0) greedy = buildToTargetError(*opt.scene, comm, options, modelPath, opt.greedy, &cache);
  const ModelBuildResult r =
      opt.greedy.targetError > 0.0 ? greedy.build : buildReducedModelFile(*opt.scene, comm, options, modelPath, &cache);
  std::vector<StageTime> stages = setup.stages();
  stages.insert(stages.end(), r.stages.begin(), r.stages.end());
  const StageTable table = gatherStages(comm, stages);
  std::string greedyFiles;
  onRootAgreed(comm, "gphr build", [&] {
    writeTextFile(artifactsDir + "/stages.csv", table.csv());
    writeTextFile(artifactsDir + "/mpi_calls.csv", table.mpiCallsCsv());
    greedyFiles = writeGreedyReport(artifactsDir, greedy, opt.scene->parameterBox().names, opt.greedy.targetError);
  });
  if (comm->getRank() == 0) {
    printBuild(modelPath, r.data, r.seconds, comm->getSize());
    printCalibration(r);
    printGreedy(greedy, opt.greedy.targetError);
    if (!greedyFiles.empty()) std::printf("  the rounds: %s in %s\n", greedyFiles.c_str(), artifactsDir.c_str());
    std::printf("%s", table.summary().c_str());
  }
  return 0;
}

}  // namespace gphr
