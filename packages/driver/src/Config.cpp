#include "gphr/driver/Config.hpp"

#include <Teuchos_XMLParameterListCoreHelpers.hpp>
#include <Teuchos_YamlParameterListCoreHelpers.hpp>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "gphr/core/Error.hpp"
#include "gphr/core/ParameterValidation.hpp"
#include "gphr/driver/InputFile.hpp"
#include "gphr/driver/RunOptions.hpp"
#include "gphr/hyper/DeimBasis.hpp"
#include "gphr/hyper/EmpiricalQuadrature.hpp"
#include "gphr/offline/ModelFileBuilder.hpp"
#include "gphr/reduction/SymplecticBasis.hpp"
#include "gphr/hyper/GpAdeimModel.hpp"
#include "gphr/models/SceneFactory.hpp"
#include "gphr/timeint/Integrator.hpp"

namespace gphr {

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
  // What depends on more than one key (the steps T / dt, the training set against the box, the
  // method, k and m lists, adeim's constraints on m, output.fieldTimes against T): the readers check it.
  runOptionsFrom(cfg);
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
  // GP-ADEIM's window wide enough for the largest m: 2k w = 40 >= m = 40 at the default k = 10, so
  // that no update leaves directions of U out (doc/design.md, "GP-ADEIM", window)
  pl.sublist("adeim").set("window", 2);
  return validateConfig(pl);
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
