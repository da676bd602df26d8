#include "gphr/driver/Config.hpp"

#include <Teuchos_XMLParameterListCoreHelpers.hpp>
#include <Teuchos_YamlParameterListCoreHelpers.hpp>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "gphr/core/Error.hpp"
#include "gphr/core/ParameterValidation.hpp"
#include "gphr/driver/FieldModels.hpp"
#include "gphr/driver/InputFile.hpp"
#include "gphr/hyper/DeimBasis.hpp"
#include "gphr/hyper/EmpiricalQuadrature.hpp"
#include "gphr/offline/ModelFileBuilder.hpp"
#include "gphr/reduction/SymplecticBasis.hpp"
#include "gphr/hyper/GpAdeimModel.hpp"
#include "gphr/models/SceneFactory.hpp"
#include "gphr/offline/Training.hpp"
#include "gphr/core/Method.hpp"
#include "gphr/online/TimeLoop.hpp"
#include "gphr/timeint/Integrator.hpp"

namespace gphr {

namespace {

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
  setIntParameter(pipe, "onlineRepeats", 1, 1, 100000,
                  "time each rom / gp-deim / deim / sdeim online run this many times and report the fastest as "
                  "t_online_s (short runs are at the mercy of scheduler and cache noise); the first run gives the "
                  "results; gp-adeim, whose model changes as it runs, runs once");
  setDoubleParameter(pipe, "onlineRepeatSeconds", 60.0, 1e-9, 1e9,
                     "time budget of the repeats of one run: a further repeat starts only while the repeats so far "
                     "took less (a run of milliseconds can then be repeated hundreds of times, to sample past the "
                     "machine's slow spells, while a minutes-long one is not repeated at all)");
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

}  // namespace

Teuchos::ParameterList validConfig(const std::string& scene) {
  Teuchos::ParameterList pl("gphr");
  pl.sublist("scene") = sceneValidParameters(scene);
  pl.sublist("parameters") = sceneParameterValidParameters(scene);
  pl.sublist("time") = sceneTimeValidParameters(scene);
  pl.sublist("integrator") = integratorValidParameters();
  sceneLinearSolverDefaults(scene, pl.sublist("integrator").sublist("linearSolver"));
  pl.sublist("training") = trainingValidParameters(static_cast<size_t>(pl.sublist("parameters").numParams()));
  pl.sublist("reduction") = basisValidParameters();
  pl.sublist("pipeline") = pipelineValidParameters();
  pl.sublist("hyper") = deimBasisValidParameters();
  pl.sublist("adeim") = adeimValidParameters();
  pl.sublist("build") = modelFileValidParameters();
  pl.sublist("eqp") = quadratureValidParameters();
  pl.sublist("output") = outputValidParameters();
  return pl;
}

TrainingOptions trainingOptionsOf(const Teuchos::ParameterList& cfg, const ParameterBox& box) {
  TrainingOptions o = trainingOptionsFrom(cfg.sublist("training"), box);
  o.dt = cfg.sublist("time").get<double>("dt");
  o.steps = wholeSteps(cfg.sublist("time").get<double>("T"), o.dt);
  o.integrator = cfg.sublist("integrator");
  return o;
}

namespace {

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
}  // namespace

Teuchos::ParameterList validateConfig(Teuchos::ParameterList cfg) {
  std::string scene = "nls1d";
  if (cfg.isSublist("scene") && cfg.sublist("scene").isType<std::string>("name"))
    scene = cfg.sublist("scene").get<std::string>("name");
  validateParameters(cfg, validConfig(scene));
  numSteps(cfg);
  trainingParameters(cfg);  // checks the training set against the box
  pipelineMethods(cfg);     // checks the method, k and m lists
  fieldModelNames(cfg);     // checks output.fieldModels
  fieldTimes(cfg);          // and output.fieldTimes against [0, T]
  return cfg;
}

Teuchos::ParameterList loadConfig(const std::string& path) {
  const bool xml = endsWith(path, ".xml");
  GPHR_REQUIRE(xml || endsWith(path, ".yaml") || endsWith(path, ".yml"), InputError, "config file '", path,
               "': the name must end in .yaml, .yml or .xml");
  const auto pl = readParameterFile(path, "config", xml);
  GPHR_REQUIRE(pl->name() == "gphr", InputError, "config file '", path,
               "': the top level must be the single key 'gphr' (found '", pl->name(), "')");
  try {
    return validateConfig(*pl);
  } catch (const InputError& e) {
    throw InputError(detail::concat("config file '", path, "': ", e.what()));
  }
}

Teuchos::ParameterList defaultConfig() {
  Teuchos::ParameterList pl("gphr");
  pl.sublist("scene").set("name", "nls1d").set("n", 256);
  pl.sublist("time").set("T", 5.0).set("dt", 0.01);
  pl.sublist("pipeline").set("rom", true);
  pl.sublist("pipeline").set("methods", Teuchos::Array<std::string>(Teuchos::tuple<std::string>("rom", "gp-deim", "gp-adeim")));
  pl.sublist("pipeline").set("m", Teuchos::Array<int>(Teuchos::tuple<int>(10, 20, 40)));
  pl.sublist("hyper").set("snapshotEvery", 5);
  pl.sublist("training").set("points", Teuchos::Array<int>(1, 3));
  return validateConfig(pl);
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

std::vector<std::vector<double>> trainingParameters(const Teuchos::ParameterList& cfg) {
  return trainingOptionsFrom(cfg.sublist("training"), makeScene(cfg.sublist("scene"))->parameterBox()).parameters;
}

std::vector<std::string> pipelineMethods(const Teuchos::ParameterList& cfg) {
  const auto& pipe = cfg.sublist("pipeline");
  std::vector<std::string> out;
  for (const auto& m : pipe.get<Teuchos::Array<std::string>>("methods")) {
    GPHR_REQUIRE(isMethod(m), InputError, "key 'pipeline.methods' has entry '", m, "'; allowed: ", methodNames());
    if (methodInfo(m).reduced() && std::find(out.begin(), out.end(), m) == out.end()) out.push_back(m);
  }
  if (pipe.get<bool>("rom") && std::find(out.begin(), out.end(), method::kRom) == out.end()) out.insert(out.begin(), method::kRom);
  // sizes >= 1, each once (a size twice would be built and run twice, and a model file cannot hold it twice)
  auto requireSizes = [](const Teuchos::Array<int>& sizes, const char* key) {
    for (Teuchos::Array<int>::size_type i = 0; i < sizes.size(); ++i) {
      GPHR_REQUIRE(sizes[i] >= 1, InputError, "key '", key, "' has entry ", sizes[i], "; allowed: integers >= 1");
      GPHR_REQUIRE(std::find(sizes.begin(), sizes.begin() + i, sizes[i]) == sizes.begin() + i, InputError, "key '",
                   key, "' has entry ", sizes[i], " twice; allowed: each size once");
    }
  };
  requireSizes(pipe.get<Teuchos::Array<int>>("k"), "pipeline.k");
  const auto& ms = pipe.get<Teuchos::Array<int>>("m");
  requireSizes(ms, "pipeline.m");
  const bool adaptive =
      std::any_of(out.begin(), out.end(), [](const std::string& m) { return methodInfo(m).adaptive(); });
  const bool wantsM =
      std::any_of(out.begin(), out.end(), [](const std::string& m) { return methodInfo(m).takesM; });
  GPHR_REQUIRE(!wantsM || !ms.empty(), InputError, "key 'pipeline.m' is empty but pipeline.methods asks for ",
               methodNames([](const MethodInfo& m) { return m.takesM; }),
               "; allowed: a list of DEIM sizes / term budgets");
  if (adaptive)
    for (int m : ms) adeimOptionsFrom(cfg.sublist("adeim"), m);  // the adeim constraints that involve m
  return out;
}

std::vector<int> pipelineK(const Teuchos::ParameterList& cfg) {
  std::vector<int> ks;
  for (int k : cfg.sublist("pipeline").get<Teuchos::Array<int>>("k")) ks.push_back(k);
  if (ks.empty()) ks.push_back(cfg.sublist("reduction").get<int>("k"));
  return ks;
}

std::string helpText() {
  std::ostringstream os;
  os << "gphr - gradient-preserving hyper-reduction of Hamiltonian systems (Trilinos)\n\n"
        "usage:\n"
        "  gphr [--output DIR]           run the small default scene (NLS, n = 256, T = 5) into DIR\n"
        "                                (default ./gphr-output)\n"
        "  gphr run CONFIG [--output DIR]  run the stages of CONFIG (.yaml/.yml/.xml), outputs in DIR\n"
        "                                (default ./gphr-output): artifacts.h5, summary.json, *.csv, *.png\n"
        "  gphr build CONFIG --model FILE.h5 [--output DIR]\n"
        "                                offline stages of CONFIG (artifacts reused from DIR) -> a reduced-model\n"
        "                                file holding only the online data (section 'build')\n"
        "  gphr query FILE.h5 QUERIES.yaml [--output DIR] [--threads N]\n"
        "                                the file's models at many parameters, spread over the ranks and\n"
        "                                N threads per rank (1 to 1024; default: the CPUs the rank may use,\n"
        "                                shared with the node's other ranks when none is bound):\n"
        "                                DIR/results.h5, DIR/queries.csv (default ./gphr-queries)\n"
        "  gphr validate FILE.h5 TESTS.yaml [--output DIR]\n"
        "                                every model of the file and the ROM against the full model at test\n"
        "                                points: DIR/validation.md (default ./gphr-validation)\n"
        "  gphr --help                   this text\n"
        "  any command: --verbose (also the timer tables), --quiet (errors only)\n"
        "  QUERIES.yaml / TESTS.yaml: doc/model-file.md\n\n"
        "CONFIG has one top-level key 'gphr'. Keys (generated from the validators):\n\n";
  for (const auto& scene : sceneNames()) {
    os << "--- scene.name: " << scene << " ---\n";
    describeParameters(validConfig(scene), os, 2);
    os << "\n";
  }
  return os.str();
}

}  // namespace gphr
