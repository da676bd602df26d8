#include "gphr/models/SceneFactory.hpp"

#include "gphr/core/Error.hpp"
#include "gphr/core/ParameterValidation.hpp"

namespace gphr {

const Teuchos::Array<std::string>& sceneNames() {
  static const Teuchos::Array<std::string> names = Teuchos::tuple<std::string>("nls1d", "nls1d-pulse", "swe2d");
  return names;
}

namespace {
void requireKnown(const std::string& name) {
  GPHR_REQUIRE(name == "nls1d" || name == "nls1d-pulse" || name == "swe2d", InputError, "key 'scene.name' has value ",
               name, "; allowed: one of 'nls1d' 'nls1d-pulse' 'swe2d'");
}
bool isNls(const std::string& name) { return name == "nls1d" || name == "nls1d-pulse"; }
}  // namespace

Teuchos::ParameterList sceneValidParameters(const std::string& name) {
  requireKnown(name);
  Teuchos::ParameterList pl("scene");
  setChoiceParameter(pl, "name", name, sceneNames(), "the scene (paper Sec. 5)");
  if (isNls(name))
    setIntParameter(pl, "n", 2048, 3, 100000000, "grid points on [-pi/0.11, pi/0.11) (paper: 2048)");
  else
    setIntParameter(pl, "nx", 50, 3, 100000, "grid points per direction on [-2, 2)^2 (paper: 50)");
  pl.set("shift", true, "shift the state by y0 and G by G(y0) (paper Sec. 3.3, eq:shiftH)");
  return pl;
}

Teuchos::ParameterList sceneParameterValidParameters(const std::string& name) {
  requireKnown(name);
  Teuchos::ParameterList pl("parameters");
  if (isNls(name)) {
    setDoubleParameter(pl, "eps", 1.0932, 0.9, 1.1, "nonlinearity strength epsilon (paper test value 1.0932)");
    if (name == "nls1d-pulse") {
      setDoubleParameter(pl, "amplitude", 1.0, 0.8, 1.2, "the pulse's amplitude a: u0 = a sqrt(2) sech(x) e^{i c x} (paper: 1)");
      setDoubleParameter(pl, "velocity", 0.5, 0.3, 0.7, "the pulse's velocity c (paper: 1/2)");
    }
  } else {
    setDoubleParameter(pl, "beta", 1.6435, 1.1, 1.7, "width of the initial Gaussian (paper test value 1.6435)");
    setDoubleParameter(pl, "gamma", 0.7762, 0.7, 1.3, "gravity-like coefficient gamma (paper test value 0.7762)");
  }
  return pl;
}

Teuchos::ParameterList sceneTimeValidParameters(const std::string& name) {
  requireKnown(name);
  Teuchos::ParameterList pl("time");
  const bool nls = isNls(name);
  setDoubleParameter(pl, "T", nls ? 30.0 : 10.0, 1e-12, 1e9, "final time (paper: 30 for NLS, 10 for SWE)");
  setDoubleParameter(pl, "dt", nls ? 0.01 : 0.005, 1e-12, 1e9, "time step (paper: 0.01 NLS, 0.005 SWE); T/dt steps");
  return pl;
}

void sceneLinearSolverDefaults(const std::string& name, Teuchos::ParameterList& linearSolver) {
  requireKnown(name);
  // The SWE's Newton matrix I - dt J Hbar is close to the identity at its time steps: one forward
  // Gauss-Seidel sweep (no factorization; linearSolver.relaxation's default) beats RILUK(1), whose
  // triangular solves were 37 % of a step and whose block-Jacobi iterations grow with the ranks of a
  // group (bench/fom_paper.sh pc, SWE 256^2, IMR, 80 steps: 5.1 s against 7.4 s on one rank, 2.6 s
  // against 5.4 s on two; GMRES per Newton 3.21 / 3.21 against 2.28 / 3.21; doc/design.md,
  // 'Preconditioner').
  // The NLS keeps RILUK(1): AMESOS2 runs one rank 1.5-1.9x faster but, under the inexact Newton,
  // with an 8x larger AVF energy drift (doc/design.md, 'Preconditioner').
  if (name != "swe2d") return;
  const Teuchos::ParameterEntry& e = linearSolver.getEntry("preconditioner");
  linearSolver.set("preconditioner", std::string("RELAXATION"), e.docString(), e.validator());
}

std::shared_ptr<Scene> makeScene(const Teuchos::ParameterList& s) {
  const std::string name = s.get<std::string>("name");
  requireKnown(name);
  if (isNls(name)) return std::make_shared<Nls1d>(s.get<int>("n"), 3.14159265358979323846 / 0.11, name == "nls1d-pulse");
  return std::make_shared<Swe2d>(s.get<int>("nx"));
}

std::vector<double> sceneParameters(const Scene& scene, const Teuchos::ParameterList& parameters) {
  std::vector<double> mu;
  for (const auto& nm : scene.parameterBox().names) mu.push_back(parameters.get<double>(nm));
  scene.parameterBox().check(mu);
  return mu;
}

}  // namespace gphr
