#include "gphr/driver/RunOptions.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>

#include <Teuchos_YamlParameterListCoreHelpers.hpp>

#include "gphr/core/Error.hpp"
#include "gphr/core/Method.hpp"
#include "gphr/core/ParameterValidation.hpp"
#include "gphr/core/Provenance.hpp"
#include "gphr/hyper/DeimBasis.hpp"
#include "gphr/hyper/EmpiricalQuadrature.hpp"
#include "gphr/models/SceneFactory.hpp"
#include "gphr/reduction/SymplecticBasis.hpp"

namespace gphr {

// The sections only the application reads: which models `gphr run` evaluates, and its outputs.
Teuchos::ParameterList pipelineValidParameters() {
  Teuchos::ParameterList pipe("pipeline");
  pipe.set("rom", false, "train, build the basis and evaluate the Galerkin reduced model beside the full model");
  pipe.set("methods", Teuchos::Array<std::string>(),
           "models to evaluate beside the full model, any of: rom, gp-deim (gradient-preserving DEIM, the paper's), "
           "gp-adeim (its adaptive variant, section adeim), deim (classic DEIM of the gradient), sdeim (DEIM with the "
           "symplectic basis, m = 2k), gp-eqp (terms and non-negative weights by NNLS, section eqp; m is its term "
           "budget), gp-eqp-refit (GP-DEIM's terms, weights refit by least squares); empty: rom if pipeline.rom");
  pipe.set("k", Teuchos::Array<int>(), "reduced half-sizes k to evaluate (2k = reducedDim); empty: reduction.k");
  pipe.set("m", Teuchos::Array<int>(), "DEIM sizes m to evaluate for gp-deim, gp-adeim and deim (each at most d); the term budgets of gp-eqp and gp-eqp-refit");
  setPassThroughSection(pipe, "mPerK",
                        "a k's own m list in place of pipeline.m: keys k<K> for a K of pipeline.k, each a list of m, "
                        "e.g. {k10: [20, 40], k40: [40, 80, 120]}; a k not named takes pipeline.m");
  setIntParameter(pipe, "onlineRepeats", 1, 1, 100000,
                  "time each rom / gp-deim / deim / sdeim online run this many times and report the fastest as "
                  "t_online_s (short runs are at the mercy of scheduler and cache noise); the first run gives the "
                  "results; gp-adeim, whose model changes as it runs, runs once");
  setDoubleParameter(pipe, "onlineRepeatSeconds", 60.0, 1e-9, 1e9,
                     "time budget of the repeats of one run: a further repeat starts only while the repeats so far "
                     "took less (a run of milliseconds can then be repeated hundreds of times, to sample past the "
                     "machine's slow spells, while a minutes-long one is not repeated at all)");
  pipe.set("errorIndicator", true,
           "estimate each reduced run's E_L2 without the full model's trajectory (E_L2_estimate in summary.json): "
           "the full scheme's residual at the lifted states carried by its linearised error equation, one residual "
           "and one linear solve of the full model per step, after the timed run (doc/error-estimate.md)");
  return pipe;
}

Teuchos::ParameterList outputValidParameters() {
  Teuchos::ParameterList out("output");
  setIntParameter(out, "saveEvery", 10, 1, 1000000000, "keep every N-th state of the trajectory in artifacts.h5");
  setDoubleParameter(out, "progressSeconds", 2.0, 0.0, 1e9, "seconds between progress lines on stderr (0: none)");
  setDoubleParameter(out, "checkpointSeconds", 60.0, 0.0, 1e9,
                     "seconds of a stage's work between checkpoints of the basis and DEIM basis PODs in "
                     "artifacts.h5.ckpt_* (0: after every training parameter / round of chunks); a killed build "
                     "loses at most about this much of a stage");
  out.set("syncArtifacts", false,
          "flush artifacts.h5 to the disk (MPI_File_sync) before each complete mark, so that a crash of the machine "
          "cannot leave a mark on data the disk lacks; off, a killed gphr loses no finished work either, and a "
          "machine crash's damage is found where the data are read (fingerprints, HDF5's checksums)");
  out.set("plots", true, "draw PNG plots with gnuplot (skipped with a note if gnuplot is missing)");
  out.set("xdmf", false,
          "write fields.xdmf (XDMF 2, for ParaView's XDMF Reader) over artifacts.h5: the full model's saved states "
          "and those of the output.fieldModels models, one field per physical component and per model, their "
          "pointwise difference to the full model, at the saved times");
  out.set("fieldModels", Teuchos::Array<std::string>(Teuchos::tuple<std::string>("rom", "best")),
          "models whose lifted states fields.png / spacetime.png and fields.xdmf show beside the full model: a "
          "method name (its most accurate run), or best (the most accurate run of any hyper-reduced method)");
  out.set("fieldTimes", Teuchos::Array<double>(),
          "times of the columns of fields.png (2-D scenes), each in [0, time.T]; the nearest saved state is shown; "
          "empty: the start, the middle and the end");
  return out;
}

long numSteps(const Teuchos::ParameterList& cfg) {
  const auto& t = cfg.sublist("time");
  const double T = t.get<double>("T"), dt = t.get<double>("dt");
  GPHR_REQUIRE(T >= dt, InputError, "key 'time.T' has value ", T, " which is smaller than time.dt = ", dt,
               "; allowed: T >= dt");
  // Before the whole-number test and before anything of the run's length is sized (the artifacts
  // file's datasets, the stored states and energies).
  GPHR_REQUIRE(T / dt <= kMaxRunSteps + 0.5, InputError, "time.T / time.dt = ", T / dt, " steps (T = ", T, ", dt = ",
               dt, "); allowed: at most ", kMaxRunSteps);
  const long steps = std::lround(T / dt);
  GPHR_REQUIRE(std::abs(steps * dt - T) <= 1e-9 * T, InputError, "key 'time.T' has value ", T,
               ", not a whole number of steps of time.dt = ", dt, "; allowed: T = k dt");
  return steps;
}

namespace {

// Sizes >= 1, each once (a size twice would be built and run twice, and a model file cannot hold it twice).
void requireSizes(const Teuchos::Array<int>& sizes, const char* key) {
  for (Teuchos::Array<int>::size_type i = 0; i < sizes.size(); ++i) {
    GPHR_REQUIRE(sizes[i] >= 1, InputError, "key '", key, "' has entry ", sizes[i], "; allowed: integers >= 1");
    GPHR_REQUIRE(std::find(sizes.begin(), sizes.begin() + i, sizes[i]) == sizes.begin() + i, InputError, "key '",
                 key, "' has entry ", sizes[i], " twice; allowed: each size once");
  }
}

// pipeline.mPerK (a section passed through: its keys are the user's k): each key k<K> with K one
// of `ks`, each value a list of sizes (a lone number is a list of one).
std::map<int, std::vector<int>> mPerKFrom(const Teuchos::ParameterList& section, const std::vector<int>& ks) {
  std::map<int, std::vector<int>> out;
  std::string kList;
  for (int k : ks) kList += (kList.empty() ? "" : ", ") + std::to_string(k);
  for (auto it = section.begin(); it != section.end(); ++it) {
    const std::string key = section.name(it), where = "pipeline.mPerK." + key;
    const bool named = key.size() > 1 && key.size() < 10 && key[0] == 'k' && key[1] != '0' &&
                       std::all_of(key.begin() + 1, key.end(), [](char c) { return c >= '0' && c <= '9'; });
    GPHR_REQUIRE(named, InputError, "key '", where, "' is not a reduced size; allowed: k<K> for a K of pipeline.k (",
                 kList, "), e.g. k", ks.front());
    const int k = std::stoi(key.substr(1));
    GPHR_REQUIRE(std::find(ks.begin(), ks.end(), k) != ks.end(), InputError, "key '", where, "' names k = ", k,
                 ", which is not evaluated; allowed: a k of pipeline.k (", kList, ")");
    const Teuchos::ParameterEntry& e = section.getEntry(key);
    Teuchos::Array<int> sizes;
    if (e.isType<Teuchos::Array<int>>()) sizes = Teuchos::getValue<Teuchos::Array<int>>(e);
    else if (e.isType<int>()) sizes.push_back(Teuchos::getValue<int>(e));
    else throw InputError(detail::concat("key '", where, "' is not a list of integers; allowed: a list of m >= 1"));
    GPHR_REQUIRE(!sizes.empty(), InputError, "key '", where, "' is empty; allowed: a list of m >= 1");
    requireSizes(sizes, where.c_str());
    out[k].assign(sizes.begin(), sizes.end());
  }
  return out;
}

bool reduced(const MethodInfo& m) { return m.reduced(); }  // the full model is always shown

}  // namespace

PipelineOptions pipelineOptionsFrom(const Teuchos::ParameterList& pipe, int reductionK) {
  PipelineOptions o;
  for (const auto& m : pipe.get<Teuchos::Array<std::string>>("methods")) {
    GPHR_REQUIRE(isMethod(m), InputError, "key 'pipeline.methods' has entry '", m, "'; allowed: ", methodNames());
    if (methodInfo(m).reduced() && std::find(o.methods.begin(), o.methods.end(), m) == o.methods.end())
      o.methods.push_back(m);
  }
  if (pipe.get<bool>("rom") && std::find(o.methods.begin(), o.methods.end(), method::kRom) == o.methods.end())
    o.methods.insert(o.methods.begin(), method::kRom);
  const auto& ks = pipe.get<Teuchos::Array<int>>("k");
  const auto& ms = pipe.get<Teuchos::Array<int>>("m");
  requireSizes(ks, "pipeline.k");
  requireSizes(ms, "pipeline.m");
  o.ks.assign(ks.begin(), ks.end());
  if (o.ks.empty()) o.ks.push_back(reductionK);
  o.ms.assign(ms.begin(), ms.end());
  o.msByK = mPerKFrom(pipe.sublist("mPerK"), o.ks);
  const bool wantsM =
      std::any_of(o.methods.begin(), o.methods.end(), [](const std::string& m) { return methodInfo(m).takesM; });
  for (int k : o.ks)
    GPHR_REQUIRE(!wantsM || !o.msOf(k).empty(), InputError, "key 'pipeline.m' is empty and pipeline.mPerK names no k",
                 k, ", but pipeline.methods asks for ", methodNames([](const MethodInfo& m) { return m.takesM; }),
                 "; allowed: a list of DEIM sizes / term budgets");
  return o;
}

OutputOptions outputOptionsFrom(const Teuchos::ParameterList& out, double T) {
  OutputOptions o;
  o.saveEvery = out.get<int>("saveEvery");
  o.progressSeconds = out.get<double>("progressSeconds");
  o.checkpointSeconds = out.get<double>("checkpointSeconds");
  o.syncArtifacts = out.get<bool>("syncArtifacts");
  o.plots = out.get<bool>("plots");
  o.xdmf = out.get<bool>("xdmf");
  for (const auto& name : out.get<Teuchos::Array<std::string>>("fieldModels")) {
    GPHR_REQUIRE(name == "best" || (isMethod(name) && methodInfo(name).reduced()), InputError,
                 "key 'output.fieldModels' has entry '", name, "'; allowed: best or one of ", methodNames(reduced));
    if (std::find(o.fieldModels.begin(), o.fieldModels.end(), name) == o.fieldModels.end()) o.fieldModels.push_back(name);
  }
  const auto& given = out.get<Teuchos::Array<double>>("fieldTimes");
  for (double t : given)
    GPHR_REQUIRE(t >= 0.0 && t <= T, InputError, "key 'output.fieldTimes' has entry ", t, "; allowed: times in [0, ", T,
                 "] (time.T)");
  o.fieldTimes = given.empty() ? std::vector<double>{0.0, 0.5 * T, T} : std::vector<double>(given.begin(), given.end());
  return o;
}

namespace {

// A validated ParameterList as JSON: sublists nested, arrays of numbers as arrays, others by value.
JsonObject configJson(const Teuchos::ParameterList& pl) {
  JsonObject j;
  for (auto it = pl.begin(); it != pl.end(); ++it) {
    const std::string& key = pl.name(it);
    if (pl.isSublist(key)) j.set(key, configJson(pl.sublist(key)));
    else if (pl.isType<bool>(key)) j.set(key, pl.get<bool>(key));
    else if (pl.isType<int>(key)) j.set(key, static_cast<long>(pl.get<int>(key)));
    else if (pl.isType<double>(key)) j.set(key, pl.get<double>(key));
    else if (pl.isType<std::string>(key)) j.set(key, pl.get<std::string>(key));
    else if (pl.isType<Teuchos::Array<int>>(key)) {
      const auto& a = pl.get<Teuchos::Array<int>>(key);
      j.set(key, std::vector<double>(a.begin(), a.end()));
    } else if (pl.isType<Teuchos::Array<double>>(key)) {
      const auto& a = pl.get<Teuchos::Array<double>>(key);
      j.set(key, std::vector<double>(a.begin(), a.end()));
    } else if (pl.isType<Teuchos::Array<std::string>>(key)) {
      std::string joined;  // the writer has no array of strings: comma-separated
      for (const auto& x : pl.get<Teuchos::Array<std::string>>(key)) joined += (joined.empty() ? "" : ",") + x;
      j.set(key, joined);
    } else {
      std::ostringstream os;
      os << pl.entry(it).getAny(false);
      j.set(key, os.str());
    }
  }
  return j;
}

// The config as run, re-readable by gphr: Teuchos' YAML reader refuses the empty arrays its writer
// emits, and an empty array is every such key's default, so they are left out.
std::string configYaml(const Teuchos::ParameterList& cfg) {
  std::function<void(Teuchos::ParameterList&)> prune = [&](Teuchos::ParameterList& pl) {
    std::vector<std::string> empty;
    for (auto it = pl.begin(); it != pl.end(); ++it) {
      const std::string& key = pl.name(it);
      if (pl.isSublist(key)) prune(pl.sublist(key));
      else if ((pl.isType<Teuchos::Array<int>>(key) && pl.get<Teuchos::Array<int>>(key).empty()) ||
               (pl.isType<Teuchos::Array<double>>(key) && pl.get<Teuchos::Array<double>>(key).empty()) ||
               (pl.isType<Teuchos::Array<std::string>>(key) && pl.get<Teuchos::Array<std::string>>(key).empty()))
        empty.push_back(key);
    }
    for (const auto& key : empty) pl.remove(key);
  };
  Teuchos::ParameterList copy(cfg);
  copy.setName("gphr");
  prune(copy);
  return toYaml(copy);
}

JsonObject provenanceOf(const Teuchos::ParameterList& cfg) {
  const auto& integ = cfg.sublist("integrator");
  const auto& ls = integ.sublist("linearSolver");
  JsonObject solvers, build;
  solvers.set("newton", integ.get<std::string>("newtonSolver"))
      .set("linear", ls.get<std::string>("method") + " + " + ls.get<std::string>("preconditioner"))
      .set("deim_indices", cfg.sublist("hyper").get<std::string>("indices"))
      .set("deim_svd", cfg.sublist("hyper").get<std::string>("svd"));
  build.set("gphr_version", gphrVersion()).set("build_type", gphrBuildType()).set("cxx_flags", gphrCxxFlags());
  JsonObject p;
  p.set("solvers", solvers).set("build", build).set("config", configJson(cfg));
  return p;
}

// A section of the config as YAML with its own name at the top.
std::string sectionYaml(const Teuchos::ParameterList& cfg, const std::string& name) {
  Teuchos::ParameterList copy(cfg.sublist(name));
  copy.setName(name);
  return toYaml(copy);
}

ConfigRecord configRecord(const Teuchos::ParameterList& cfg) {
  ConfigRecord r;
  r.yaml = configYaml(cfg);
  r.fullYaml = toYaml(cfg);
  r.integratorYaml = sectionYaml(cfg, "integrator");
  r.provenance = provenanceOf(cfg);
  return r;
}

// The training, basis, DEIM basis and fit options: the stages' own readers, the time step, steps
// and integrator from the time and integrator sections, the basis built for the largest k asked.
OfflineOptions offlineOptionsFrom(const Teuchos::ParameterList& cfg, const Scene& scene, const PipelineOptions& p) {
  OfflineOptions o;
  o.training = trainingOptionsFrom(cfg.sublist("training"), scene.parameterBox());
  o.training.dt = cfg.sublist("time").get<double>("dt");
  o.training.steps = numSteps(cfg);
  o.training.integrator = cfg.sublist("integrator");
  const int basisK = std::max(cfg.sublist("reduction").get<int>("k"), *std::max_element(p.ks.begin(), p.ks.end()));
  o.basis = basisOptionsFrom(cfg.sublist("reduction"), basisK);
  o.ks = p.ks;
  o.ms = p.ms;
  o.msByK = p.msByK;
  o.deim = deimBasisOptionsFrom(cfg.sublist("hyper"), o.allMs().empty() ? 0 : o.allMs().back());
  o.eqp = quadratureOptionsFrom(cfg.sublist("eqp"));
  o.eqpTolerance = cfg.sublist("eqp").get<double>("tolerance");
  o.sceneConfig = sectionYaml(cfg, "scene");
  return o;
}

EvaluationSettings evaluationSettingsFrom(const Teuchos::ParameterList& cfg, const OutputOptions& out) {
  EvaluationSettings s;
  s.time.dt = cfg.sublist("time").get<double>("dt");
  s.time.steps = numSteps(cfg);
  s.time.integrator = cfg.sublist("integrator");
  s.saveEvery = out.saveEvery;
  s.progressSeconds = out.progressSeconds;
  s.onlineRepeats = cfg.sublist("pipeline").get<int>("onlineRepeats");
  s.onlineRepeatSeconds = cfg.sublist("pipeline").get<double>("onlineRepeatSeconds");
  s.shift = cfg.sublist("scene").get<bool>("shift");
  s.errorIndicator = cfg.sublist("pipeline").get<bool>("errorIndicator");
  return s;
}

}  // namespace

RunOptions runOptionsFrom(const Teuchos::ParameterList& cfg) {
  RunOptions o;
  o.scene = makeScene(cfg.sublist("scene"));
  o.mu = sceneParameters(*o.scene, cfg.sublist("parameters"));
  o.T = cfg.sublist("time").get<double>("T");
  o.scheme = cfg.sublist("integrator").get<std::string>("scheme");
  o.pipeline = pipelineOptionsFrom(cfg.sublist("pipeline"), cfg.sublist("reduction").get<int>("k"));
  o.output = outputOptionsFrom(cfg.sublist("output"), o.T);
  o.evaluation = evaluationSettingsFrom(cfg, o.output);
  o.offline = offlineOptionsFrom(cfg, *o.scene, o.pipeline);
  const auto& hyper = cfg.sublist("hyper");
  o.indices = hyper.get<std::string>("indices");
  o.deimSnapshots = hyper.get<std::string>("deimSnapshots") == "full" ? GradientSnapshots::Full : GradientSnapshots::Projected;
  o.adeim = adeimOptionsFrom(cfg.sublist("adeim"));
  if (std::any_of(o.pipeline.methods.begin(), o.pipeline.methods.end(),
                  [](const std::string& m) { return methodInfo(m).adaptive(); }))
    for (int m : o.pipeline.allMs()) adeimOptionsFor(o.adeim, m);  // the adeim constraints that involve m
  o.record = configRecord(cfg);
  o.file = modelFileOptionsFrom(cfg.sublist("build"));
  o.file.indices = o.indices;
  o.file.integratorConfig = o.record.integratorYaml;
  o.withBasis = cfg.sublist("build").get<bool>("withBasis");
  const auto& build = cfg.sublist("build");
  o.greedy.targetError = o.file.targetError;
  o.greedy.candidates = build.get<int>("candidates");
  o.greedy.seed = static_cast<unsigned long>(build.get<int>("candidateSeed"));
  o.greedy.maxPoints = build.get<int>("maxTrainingPoints");
  o.greedy.confirmPoints = build.get<int>("confirmPoints");
  o.greedy.start = build.get<std::string>("greedyStart");
  o.greedy.pointsPerRound = build.get<int>("pointsPerRound");
  return o;
}

}  // namespace gphr
