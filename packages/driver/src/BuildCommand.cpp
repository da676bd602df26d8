// `gphr build CONFIG --model FILE.h5`: the offline stages of `gphr run` (training, basis, DEIM
// basis, reusing DIR/artifacts.h5) for every k and m of the pipeline, then the reduced-model file:
// per k the parameter interpolant of L_r, f_r, c and the reference rows (doc/model-file.md), per
// gp-deim (k, m) its sample mesh. The full model is not evaluated.
#include <Teuchos_Time.hpp>

#include <filesystem>
#include <iterator>

#include "gphr/core/Error.hpp"
#include "gphr/driver/Commands.hpp"
#include "gphr/driver/Config.hpp"
#include "gphr/driver/ModelEvaluation.hpp"
#include "gphr/driver/ModelFileBuilder.hpp"
#include "gphr/driver/OutputLock.hpp"
#include "gphr/driver/Pipeline.hpp"
#include "gphr/models/SceneFactory.hpp"
#include "gphr/online/Method.hpp"

namespace gphr {

namespace {

// A section of the config as YAML with its own name at the top.
std::string sectionYaml(const Teuchos::ParameterList& cfg, const std::string& name) {
  Teuchos::ParameterList copy(cfg.sublist(name));
  copy.setName(name);
  return toYaml(copy);
}

// gp-adeim is stored as its options: its queries build the full system and sample its residual
// online (alg:SP-ADEIM), from the basis in the file and the first delta0 full-model steps.
void addAdeimModels(const RunContext& ctx, int k, const std::vector<int>& ms, std::vector<StoredHyperModel>& out) {
  const auto& cfg = ctx.config;
  std::string why;
  if (!cfg.sublist("build").get<bool>("withBasis")) why = "its queries need the basis (build.withBasis: true)";
  else if (cfg.sublist("adeim").get<std::string>("initialBasis") != "fom")
    why = "adeim.initialBasis 'training' needs the training DEIM basis online, which the file does not hold";
  if (!why.empty()) {
    if (ctx.comm->getRank() == 0) std::fprintf(stderr, "[gphr] build: gp-adeim not stored: %s\n", why.c_str());
    return;
  }
  for (int m : ms) {
    StoredHyperModel sm;
    sm.method = "gp-adeim", sm.k = k, sm.m = m;
    adeimOptionsFrom(cfg.sublist("adeim"), m);  // the constraints that involve m, checked now
    sm.adeimConfig = sectionYaml(cfg, "adeim");
    out.push_back(sm);
  }
}

// The stored models of reduced size k: gp-deim from the DEIM basis, gp-adeim as its options, gp-eqp /
// gp-eqp-refit from their fits (a budget the training cannot support is left out, with a note).
std::vector<StoredHyperModel> modelsOfK(const RunContext& ctx, RomStages& st, const SceneInstance& inst,
                                        const MultiVector& A, int k, const std::vector<std::string>& methods,
                                        const std::vector<int>& ms) {
  std::vector<StoredHyperModel> out;
  for (const auto& method : methods) {
    if (method == "gp-adeim") {
      addAdeimModels(ctx, k, ms, out);
      continue;
    }
    if (method == "gp-deim") {
      const auto U = deimBasisFor(ctx, st, A, k, *inst.system).basis.U;
      auto deim = gpDeimModels(inst, A, k, *U, ms, ctx.config.sublist("hyper").get<std::string>("indices"));
      std::move(deim.begin(), deim.end(), std::back_inserter(out));
      continue;
    }
    std::map<int, std::string> skipped;
    for (const auto& [m, fit] : termWeightFits(ctx, st, A, k, *inst.system, method, ms, skipped))
      out.push_back(termModel(inst, A, method, k, m, fit.terms, fit.weights));
    if (ctx.comm->getRank() == 0)
      for (const auto& [m, why] : skipped)
        std::fprintf(stderr, "[gphr] build: %s k = %d, m = %d not stored: %s\n", method.c_str(), k, m, why.c_str());
  }
  return out;
}

ModelFileOptions fileOptions(const Teuchos::ParameterList& cfg) {
  ModelFileOptions o;
  for (int g : cfg.sublist("build").get<Teuchos::Array<int>>("probes")) o.probes.push_back(g);
  o.interpolationNodes = cfg.sublist("build").get<int>("interpolationNodes");
  o.indices = cfg.sublist("hyper").get<std::string>("indices");
  o.integratorConfig = sectionYaml(cfg, "integrator");
  return o;
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

int runBuild(const std::string& configPath, const std::string& modelPath, const std::string& artifactsDir,
             const RCP<const Comm>& comm) {
  const bool root = comm->getRank() == 0;
  RunContext ctx;
  ctx.config = loadConfig(configPath);
  ctx.scene = makeScene(ctx.config.sublist("scene"));
  ctx.mu = sceneParameters(*ctx.scene, ctx.config.sublist("parameters"));
  ctx.comm = comm;
  ctx.outputDir = artifactsDir;
  std::vector<std::string> stored, skipped;
  for (const auto& m : pipelineMethods(ctx.config)) (methodInfo(m).storable ? stored : skipped).push_back(m);
  GPHR_REQUIRE(!stored.empty(), InputError, "config file '", configPath,
               "': gphr build stores ", methodNames([](const MethodInfo& m) { return m.storable; }),
               " models; pipeline.methods must list one of them");
  GPHR_REQUIRE(ctx.config.sublist("scene").get<bool>("shift"), InputError, "config file '", configPath,
               "': gphr build needs scene.shift: true (the stored models are of the shifted system)");
  prepareOutputDir(ctx, false);
  const OutputLock lock(artifactsDir, "build", comm);
  const auto parent = std::filesystem::path(modelPath).parent_path();
  if (!parent.empty()) makeDirectory(parent.string(), comm);
  if (root && !skipped.empty())
    for (const auto& m : skipped)
      std::fprintf(stderr, "[gphr] build: %s is not stored (%s)\n", m.c_str(),
                   "its online model needs all d rows or is a baseline: run it with gphr run");
  Teuchos::Time clock("build");
  clock.start();
  RomStages st;
  st.training = runTraining(ctx);
  st.basis = runReduction(ctx, st.training, st.basisCached);
  const auto inst = ctx.scene->instantiate(comm, ctx.mu, true);
  const ModelFileOptions opt = fileOptions(ctx.config);
  ReducedModelData data = modelFileHeader(*ctx.scene, inst, opt);
  data.sceneConfig = sectionYaml(ctx.config, "scene");
  data.config = toYaml(ctx.config);
  data.T = ctx.config.sublist("time").get<double>("T");
  data.dt = ctx.config.sublist("time").get<double>("dt");
  std::vector<int> ms;
  for (int m : ctx.config.sublist("pipeline").get<Teuchos::Array<int>>("m")) ms.push_back(m);
  std::vector<RCP<const MultiVector>> bases;
  const bool withBasis = ctx.config.sublist("build").get<bool>("withBasis");
  for (int k : stageK(ctx.config, st.basis)) {
    const auto A = leadingBasis(st.basis, k);
    addReducedBasis(data, *ctx.scene, inst, *A, k, modelsOfK(ctx, st, inst, *A, k, stored, ms), opt);
    bases.push_back(withBasis ? RCP<const MultiVector>(A) : Teuchos::null);
  }
  data.offlineSeconds = clock.totalElapsedTime(true);
  writeReducedModelFile(modelPath, comm, data, bases, &inst.system->space());
  const double seconds = clock.stop();
  if (root) printBuild(modelPath, data, seconds, comm->getSize());
  return 0;
}

}  // namespace gphr
