#include "gphr/driver/Config.hpp"

#include <Teuchos_XMLParameterListCoreHelpers.hpp>
#include <Teuchos_YamlParameterListCoreHelpers.hpp>
#include <cmath>
#include <fstream>
#include <sstream>

#include "gphr/core/Error.hpp"
#include "gphr/core/ParameterValidation.hpp"
#include "gphr/models/SceneFactory.hpp"
#include "gphr/timeint/Integrator.hpp"

namespace gphr {

Teuchos::ParameterList configValidParameters(const std::string& scene) {
  Teuchos::ParameterList pl("gphr");
  pl.sublist("scene") = sceneValidParameters(scene);
  pl.sublist("parameters") = sceneParameterValidParameters(scene);
  pl.sublist("time") = sceneTimeValidParameters(scene);
  pl.sublist("integrator") = integratorValidParameters();
  auto& out = pl.sublist("output");
  setIntParameter(out, "saveEvery", 10, 1, 1000000000, "keep every N-th state of the trajectory in artifacts.h5");
  setDoubleParameter(out, "progressSeconds", 2.0, 0.0, 1e9, "seconds between progress lines on stderr (0: none)");
  out.set("plots", true, "draw PNG plots with gnuplot (skipped with a note if gnuplot is missing)");
  return pl;
}

namespace {
std::string firstLine(const std::string& s) {
  std::string line = s.substr(0, s.find('\n'));
  // Teuchos prefixes "file:line:\n\n Throw number..."; prefer the line that names the problem.
  const auto pos = s.find("Parser failure");
  if (pos != std::string::npos) line = s.substr(pos, s.find('\n', pos) - pos);
  return line;
}

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
}  // namespace

Teuchos::ParameterList validateConfig(Teuchos::ParameterList cfg) {
  std::string scene = "nls1d";
  if (cfg.isSublist("scene") && cfg.sublist("scene").isType<std::string>("name"))
    scene = cfg.sublist("scene").get<std::string>("name");
  validateParameters(cfg, configValidParameters(scene));
  numSteps(cfg);
  return cfg;
}

Teuchos::ParameterList loadConfig(const std::string& path) {
  GPHR_REQUIRE(std::ifstream(path).good(), InputError, "cannot read config file '", path, "'");
  Teuchos::RCP<Teuchos::ParameterList> pl;
  const bool xml = endsWith(path, ".xml");
  GPHR_REQUIRE(xml || endsWith(path, ".yaml") || endsWith(path, ".yml"), InputError, "config file '", path,
               "': the name must end in .yaml, .yml or .xml");
  try {
    pl = xml ? Teuchos::getParametersFromXmlFile(path) : Teuchos::getParametersFromYamlFile(path);
  } catch (const std::exception& e) {
    throw InputError(detail::concat("config file '", path, "' is malformed ", xml ? "XML" : "YAML", ": ",
                                    firstLine(e.what())));
  }
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
  return validateConfig(pl);
}

long numSteps(const Teuchos::ParameterList& cfg) {
  const auto& t = cfg.sublist("time");
  const double T = t.get<double>("T"), dt = t.get<double>("dt");
  GPHR_REQUIRE(T >= dt, InputError, "key 'time.T' has value ", T, " which is smaller than time.dt = ", dt,
               "; allowed: T >= dt");
  const long steps = std::lround(T / dt);
  GPHR_REQUIRE(std::abs(steps * dt - T) <= 1e-9 * T, InputError, "key 'time.T' has value ", T,
               ", not a whole number of steps of time.dt = ", dt, "; allowed: T = k dt");
  return steps;
}

std::string helpText() {
  std::ostringstream os;
  os << "gphr - gradient-preserving hyper-reduction of Hamiltonian systems (Trilinos)\n\n"
        "usage:\n"
        "  gphr [--output DIR]           run the small default scene (NLS, n = 256, T = 5) into DIR\n"
        "                                (default ./gphr-output)\n"
        "  gphr run CONFIG [--output DIR]  run the stages of CONFIG (.yaml/.yml/.xml), outputs in DIR\n"
        "                                (default ./gphr-output): artifacts.h5, summary.json, *.csv, *.png\n"
        "  gphr --help                   this text\n\n"
        "CONFIG has one top-level key 'gphr'. Keys (generated from the validators):\n\n";
  for (const auto& scene : sceneNames()) {
    os << "--- scene.name: " << scene << " ---\n";
    describeParameters(configValidParameters(scene), os, 2);
    os << "\n";
  }
  return os.str();
}

}  // namespace gphr
