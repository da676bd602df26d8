#include "gphr/offline/ModelFileBuild.hpp"

#include <Teuchos_Time.hpp>
#include <algorithm>
#include <cstdio>
#include <iterator>
#include <memory>

#include "gphr/core/Error.hpp"
#include "gphr/core/Provenance.hpp"
#include "gphr/hyper/GpAdeimModel.hpp"
#include "gphr/offline/DeimBasisStage.hpp"
#include "gphr/offline/TermWeightFits.hpp"
#include "gphr/core/Method.hpp"
#include "gphr/reduction/Deim.hpp"

namespace gphr {

namespace {

// What the stages of one k share.
struct BuildState {
  const Scene& scene;
  const RCP<const Comm>& comm;
  const ModelBuildOptions& options;
  const ArtifactsCache* cache;
  const TrainingResult& training;
  const SceneInstance& instance;
  StageClocks& clocks;
};

std::string ofK(const char* stage, int k) { return std::string(stage) + " k=" + std::to_string(k); }

int largest(const std::vector<int>& ms) { return ms.empty() ? 0 : *std::max_element(ms.begin(), ms.end()); }

// Why gp-adeim cannot be stored with these options ("": it can).
std::string whyNoAdeim(const ModelBuildOptions& o) {
  if (!o.withBasis) return "its queries need the basis (build.withBasis: true)";
  if (o.adeim.isParameter("initialBasis") && o.adeim.get<std::string>("initialBasis") != "fom")
    return "adeim.initialBasis 'training' needs the training DEIM basis online, which the file does not hold";
  return "";
}

// gp-adeim is stored as its options: its queries build the full system and sample its residual
// online (alg:SP-ADEIM), from the basis in the file and the first delta0 full-model steps.
void addAdeimModels(const BuildState& b, int k, std::vector<StoredHyperModel>& out) {
  const auto& o = b.options;
  const std::string why = whyNoAdeim(o);
  if (!why.empty()) {
    if (b.comm->getRank() == 0) std::fprintf(stderr, "[gphr] build: gp-adeim not stored: %s\n", why.c_str());
    return;
  }
  Teuchos::ParameterList section(o.adeim);
  section.setName("adeim");
  for (int m : o.ms) {
    StoredHyperModel sm;
    sm.method = method::kGpAdeim, sm.k = k, sm.m = m;
    adeimOptionsFrom(section, m);  // the constraints that involve m, checked now
    sm.adeimConfig = toYaml(section);
    out.push_back(sm);
  }
}

// Timed from outside: the DEIM basis stage's internals are its own.
RCP<const MultiVector> deimBasisOf(const BuildState& b, const MultiVector& A, int k) {
  const StageClocks::Scope clock(b.clocks, ofK("deim basis", k));
  DeimBasisOptions opt = b.options.deim;
  if (opt.largestM == 0) opt.largestM = largest(b.options.ms);  // what maxRank 0 keeps room for (deimMaxRank)
  return runDeimBasisStage(b.scene, b.comm, b.training, A, *b.instance.system, opt, b.cache, b.options.keys.deim).basis.U;
}

// The stored models of reduced size k: gp-deim from the DEIM basis, gp-adeim as its options,
// gp-eqp / gp-eqp-refit from their fits (a budget the training cannot support is left out, with a note).
std::vector<StoredHyperModel> modelsOfK(const BuildState& b, const MultiVector& A, int k) {
  const auto& o = b.options;
  std::vector<StoredHyperModel> out;
  RCP<const MultiVector> U;  // the DEIM basis, computed on first need
  auto deimBasis = [&] { return U.is_null() ? (U = deimBasisOf(b, A, k)) : U; };
  std::unique_ptr<TermWeightFits> fits;  // both term-weight methods' fits share its training system
  for (const auto& method : o.methods) {
    const MethodInfo& info = methodInfo(method);
    if (info.adaptive()) {
      addAdeimModels(b, k, out);
    } else if (info.fit == TermWeightFit::Deim) {
      const auto& basis = *deimBasis();
      const StageClocks::Scope clock(b.clocks, ofK("gp-deim", k));
      auto deim = gpDeimModels(b.instance, A, k, basis, o.ms, o.file.indices);
      std::move(deim.begin(), deim.end(), std::back_inserter(out));
    } else {
      // A DEIM basis the fits ask for inside is a stage of its own (nested scopes exclude it).
      const StageClocks::Scope clock(b.clocks, ofK("fits", k));
      if (!fits)
        fits = std::make_unique<TermWeightFits>(
            b.scene, b.comm, b.training, A, o.eqp, o.eqpTolerance, o.ms,
            [&](int m) { return selectDeimIndices(*deimBasis(), m, o.file.indices); }, b.cache, o.keys.nnls,
            o.keys.refit);
      std::map<int, std::string> skipped;
      for (const auto& [m, fit] : fits->all(method, o.ms, skipped))
        out.push_back(termModel(b.instance, A, method, k, m, fit.terms, fit.weights));
      if (b.comm->getRank() == 0)
        for (const auto& [m, why] : skipped)
          std::fprintf(stderr, "[gphr] build: %s k = %d, m = %d not stored: %s\n", method.c_str(), k, m, why.c_str());
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
  GPHR_REQUIRE(!o.ms.empty(), InputError, "no DEIM size m given; allowed: one or more m >= 1");
  for (int m : o.ms) GPHR_REQUIRE(m >= 1, InputError, "DEIM size m = ", m, "; allowed: m >= 1");
  GPHR_REQUIRE(o.parameter.empty() || o.parameter.size() == scene.parameterBox().names.size(), InputError,
               "the instance parameter has ", o.parameter.size(), " values; allowed: ", scene.parameterBox().names.size(),
               " (one per parameter of the box)");
  for (GO p : o.file.probes)
    GPHR_REQUIRE(fullDim <= 0 || (p >= 0 && p < fullDim), InputError, "probe entry ", p,
                 " is not a state entry; allowed: 0 to ", fullDim - 1);
  const int largestK = o.ks.empty() ? 0 : *std::max_element(o.ks.begin(), o.ks.end());
  checkBasisSizeBeforeTraining(o.training, o.basis, std::max(o.basis.k, largestK), fullDim);  // before the training
}

namespace {

std::vector<double> boxCentre(const ParameterBox& box) {
  std::vector<double> c;
  for (const auto& [lo, hi] : box.bounds) c.push_back(0.5 * (lo + hi));
  return c;
}

}  // namespace

ModelBuildResult buildReducedModelFile(const Scene& scene, const RCP<const Comm>& comm,
                                       const ModelBuildOptions& options, const std::string& path,
                                       const ArtifactsCache* cache) {
  checkModelBuildOptions(scene, options);
  Teuchos::Time clock("build");
  clock.start();
  ModelBuildResult r;
  StageClocks clocks;
  using Scope = StageClocks::Scope;
  {
    const Scope stage(clocks, "training");
    r.training = runTraining(scene, comm, options.training, cache, options.keys.training);
  }
  const auto mu = options.parameter.empty() ? boxCentre(scene.parameterBox()) : options.parameter;
  const auto inst = [&] {
    const Scope stage(clocks, "instance");
    return scene.instantiate(comm, mu, true);
  }();
  {
    const Scope stage(clocks, "basis");
    r.basis = runBasisStage(r.training, inst.system->space(), options.basis, scene.name(), cache, options.keys.basis);
  }
  ReducedModelData& data = r.data;
  {
    const Scope stage(clocks, "header");
    data = modelFileHeader(scene, inst, options.file);
  }
  data.sceneConfig = options.sceneConfig;
  data.config = options.config;
  data.dt = options.training.dt;
  data.T = options.T > 0.0 ? options.T : options.training.dt * options.training.steps;
  const BuildState state{scene, comm, options, cache, r.training, inst, clocks};
  std::vector<RCP<const MultiVector>> bases;
  for (int k : basisSizes(options.ks.empty() ? std::vector<int>{0} : options.ks, r.basis.basis)) {
    const auto A = leadingBasis(r.basis.basis, k);
    auto models = modelsOfK(state, *A, k);
    {
      const Scope stage(clocks, ofK("interpolation", k));
      addReducedBasis(data, scene, inst, *A, k, std::move(models), options.file);
    }
    bases.push_back(options.withBasis ? RCP<const MultiVector>(A) : Teuchos::null);
  }
  data.offlineSeconds = clock.totalElapsedTime(true);
  {
    const Scope stage(clocks, "write");
    writeReducedModelFile(path, comm, data, bases, &inst.system->space());
  }
  r.seconds = clock.stop();
  r.stages = clocks.stages();
  return r;
}

}  // namespace gphr
