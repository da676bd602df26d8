#include "gphr/offline/ModelFileBuild.hpp"

#include "gphr/offline/ErrorCalibration.hpp"

#include <Teuchos_Time.hpp>
#include <algorithm>
#include <cstdio>
#include <iterator>
#include <memory>

#include "gphr/core/Error.hpp"
#include "gphr/core/Provenance.hpp"
#include "gphr/hyper/GpAdeimModel.hpp"
#include "gphr/core/Method.hpp"
#include "gphr/reduction/Deim.hpp"

namespace gphr {

namespace {

std::string ofK(const char* stage, int k) { return std::string(stage) + " k=" + std::to_string(k); }

// Why gp-adeim cannot be stored with these options ("": it can).
std::string whyNoAdeim(const ModelBuildOptions& o) {
  if (!o.withBasis) return "its queries need the basis (build.withBasis: true)";
  if (o.adeim.initialBasis != "fom")
    return "adeim.initialBasis 'training' needs the training DEIM basis online, which the file does not hold";
  return "";
}

// gp-adeim is stored as its options: its queries build the full system and sample its residual
// online (alg:SP-ADEIM), from the basis in the file and the first delta0 full-model steps.
void addAdeimModels(const ModelBuildOptions& o, const RCP<const Comm>& comm, int k, std::vector<StoredHyperModel>& out) {
  const std::string why = whyNoAdeim(o);
  if (!why.empty()) {
    if (comm->getRank() == 0) std::fprintf(stderr, "[gphr] build: gp-adeim not stored: %s\n", why.c_str());
    return;
  }
  for (int m : o.msOf(k)) {
    StoredHyperModel sm;
    sm.method = method::kGpAdeim, sm.k = k, sm.m = m;
    adeimOptionsFor(o.adeim, m);  // the constraints that involve m, checked now
    sm.adeimConfig = toYaml(adeimParameters(o.adeim));
    out.push_back(sm);
  }
}

// gp-deim's models of size k: those of the m the DEIM basis holds; a larger m is left out and
// said in `skipped`, as `gphr run` marks it unavailable.
std::vector<StoredHyperModel> gpDeimModelsOfK(OfflineSequence& seq, const ModelBuildOptions& o, int k,
                                              std::vector<std::string>& skipped) {
  const auto& basis = *seq.deimBasis(k).basis.U;
  const int vectors = static_cast<int>(basis.getNumVectors());
  std::vector<int> ms;
  for (int m : o.msOf(k))
    if (m <= vectors) ms.push_back(m);
    else
      skipped.push_back(detail::concat("gp-deim k = ", k, ", m = ", m, ": the DEIM basis has ", vectors,
                                       " vectors (numerical rank of the snapshots or hyper.maxRank)"));
  const StageClocks::Scope clock(seq.clocks(), ofK("gp-deim", k));
  return gpDeimModels(seq.instance(), *seq.reducedBasis(k), k, basis, ms, o.file.indices);
}

// The stored models of reduced size k: gp-deim from the DEIM basis, gp-adeim as its options,
// gp-eqp / gp-eqp-refit from their fits. What cannot be built (an m past the DEIM basis, a budget
// the training cannot support) is left out and said in `skipped`.
std::vector<StoredHyperModel> modelsOfK(OfflineSequence& seq, const ModelBuildOptions& o, int k,
                                        std::vector<std::string>& skipped) {
  std::vector<StoredHyperModel> out;
  const auto A = seq.reducedBasis(k);
  const SceneInstance& inst = seq.instance();
  for (const auto& method : o.methods) {
    const MethodInfo& info = methodInfo(method);
    if (info.adaptive()) {
      addAdeimModels(o, seq.comm(), k, out);
    } else if (info.fit == TermWeightFit::Deim) {
      auto deim = gpDeimModelsOfK(seq, o, k, skipped);
      std::move(deim.begin(), deim.end(), std::back_inserter(out));
    } else {
      // A DEIM basis the fits ask for inside is a stage of its own (nested scopes exclude it).
      const StageClocks::Scope clock(seq.clocks(), ofK("fits", k));
      std::map<int, std::string> unfit;
      for (const auto& [m, fit] : seq.termWeightFits(k, o.file.indices).all(method, o.msOf(k), unfit))
        out.push_back(termModel(inst, *A, method, k, m, fit.terms, fit.weights));
      for (const auto& [m, why] : unfit) skipped.push_back(detail::concat(method, " k = ", k, ", m = ", m, ": ", why));
    }
  }
  return out;
}

}  // namespace

void checkModelBuildOptions(const Scene& scene, const ModelBuildOptions& o, GO fullDim) {
  GPHR_REQUIRE(!o.methods.empty(), InputError, "the offline phase stores ",
               methodNames([](const MethodInfo& m) { return m.storable; }), " models; none was asked for");
  for (const auto& m : o.methods)
    GPHR_REQUIRE(methodInfo(m).storable, InputError, "method '", m, "' cannot be stored in a reduced-model file; allowed: ",
                 methodNames([](const MethodInfo& mi) { return mi.storable; }));
  // gp-adeim alone, unstorable: refused now, not after the training with "no model for k"
  GPHR_REQUIRE(o.methods != std::vector<std::string>{method::kGpAdeim} || whyNoAdeim(o).empty(), InputError,
               "gp-adeim, the only method asked for, cannot be stored: ", whyNoAdeim(o));
  for (int k : o.ks)
    GPHR_REQUIRE(!o.msOf(k).empty(), InputError, "no DEIM size m given for k = ", k, "; allowed: one or more m >= 1");
  GPHR_REQUIRE(!o.allMs().empty(), InputError, "no DEIM size m given; allowed: one or more m >= 1");
  for (int m : o.allMs()) GPHR_REQUIRE(m >= 1, InputError, "DEIM size m = ", m, "; allowed: m >= 1");
  for (const auto& [k, list] : o.msByK)
    GPHR_REQUIRE(std::find(o.ks.begin(), o.ks.end(), k) != o.ks.end(), InputError, "DEIM sizes given for k = ", k,
                 ", which is not among the reduced sizes built; allowed: a k of the build's k list");
  GPHR_REQUIRE(o.parameter.empty() || o.parameter.size() == scene.parameterBox().names.size(), InputError,
               "the instance parameter has ", o.parameter.size(), " values; allowed: ", scene.parameterBox().names.size(),
               " (one per parameter of the box)");
  for (GO p : o.file.probes)
    GPHR_REQUIRE(fullDim <= 0 || (p >= 0 && p < fullDim), InputError, "probe entry ", p,
                 " is not a state entry; allowed: 0 to ", fullDim - 1);
  const int largestK = o.ks.empty() ? 0 : *std::max_element(o.ks.begin(), o.ks.end());
  checkBasisSizeBeforeTraining(o.training, o.basis, std::max(o.basis.k, largestK), fullDim);  // before the training
}

ModelBuildResult buildReducedModelFile(const Scene& scene, const RCP<const Comm>& comm,
                                       const ModelBuildOptions& options, const std::string& path,
                                       const ArtifactsCache* cache, const OfflineSequence::StageHook& hook) {
  checkModelBuildOptions(scene, options);
  Teuchos::Time clock("build");
  clock.start();
  OfflineSequence seq(scene, comm, options, options.parameter, cache);
  std::vector<std::string> cached;  // the file says which stages' seconds were a cache read's
  seq.setStageHook([&](const OfflineStageEnd& end) {
    if (end.cached) cached.push_back(end.name);
    if (hook) hook(end);
  });
  ModelBuildResult r;
  r.training = seq.training();
  const SceneInstance& inst = seq.instance();
  r.basis = seq.basis();
  ReducedModelData& data = r.data;
  {
    const StageClocks::Scope stage(seq.clocks(), "header");
    data = modelFileHeader(scene, inst, options.file);
  }
  data.sceneConfig = options.sceneConfig;
  data.config = options.config;
  data.dt = options.training.dt;
  data.T = options.T > 0.0 ? options.T : options.training.dt * options.training.steps;
  std::vector<RCP<const MultiVector>> bases;
  for (int k : seq.sizes()) {
    const size_t before = r.skipped.size();
    auto models = modelsOfK(seq, options, k, r.skipped);
    if (models.empty()) r.skipped.push_back(detail::concat("k = ", k, ": no model of this size (its basis is not stored)"));
    if (comm->getRank() == 0)
      for (size_t i = before; i < r.skipped.size(); ++i)
        std::fprintf(stderr, "[gphr] build: not stored: %s\n", r.skipped[i].c_str());
    if (models.empty()) continue;
    const auto A = seq.reducedBasis(k);
    {
      const StageClocks::Scope stage(seq.clocks(), ofK("interpolation", k));
      addReducedBasis(data, scene, inst, *A, k, std::move(models), options.file);
    }
    bases.push_back(options.withBasis ? A : Teuchos::null);
  }
  GPHR_REQUIRE(!data.bases.empty(), InputError, "reduced-model file '", path, "': no model could be built (",
               r.skipped.size(), " left out, said above); allowed: m the DEIM basis holds, budgets the training supports");
  data.targetError = options.file.targetError;
  data.greedy = options.greedyRounds;
  data.queryDefaults = options.queryDefaults;
  data.trainingParameters = r.training.parameters;
  data.cachedStages = cached;
  if (options.file.indicatorDofs > 0) {
    const StageClocks::Scope stage(seq.clocks(), "calibration");
    std::map<int, RCP<const MultiVector>> byK;
    for (const auto& b : data.bases) byK[b.k] = seq.reducedBasis(b.k);
    if (comm->getRank() == 0 && options.training.progress)
      std::fprintf(stderr, "[gphr] build: calibrating the error indicators: %zu models at %zu training parameters\n",
                   data.models.size(), r.training.parameters.size());
    r.calibration = calibrateErrorIndicators(data, scene, *inst.system, byK, r.training,
                                             options.training.snapshotEvery, options.training.dt,
                                             options.training.steps);
  }
  data.offlineSeconds = options.earlierSeconds + clock.totalElapsedTime(true);
  {
    const StageClocks::Scope stage(seq.clocks(), "write");
    writeReducedModelFile(path, comm, data, bases, &inst.system->space());
  }
  r.seconds = clock.stop();
  r.stages = seq.clocks().stages();
  return r;
}

}  // namespace gphr
