#include "gphr/driver/FomStage.hpp"

#include <Teuchos_Time.hpp>
#include <algorithm>
#include <cmath>
#include <iostream>

#include "gphr/driver/Config.hpp"
#include "gphr/driver/FieldModels.hpp"
#include "gphr/core/Error.hpp"
#include "gphr/online/TimeLoop.hpp"
#include "gphr/timeint/FullModelIntegrator.hpp"
#include "gphr/core/Method.hpp"

namespace gphr {

namespace {
// Progress on stderr (rank 0) at most every `every` seconds: step, time, elapsed, estimate left.
class Progress {
 public:
  Progress(std::string label, long total, double every, bool root)
      : label_(std::move(label)), total_(total), every_(every), root_(root), clock_("progress") {
    clock_.start();
  }
  void update(long step, double t) {
    const double el = clock_.totalElapsedTime(true);
    if (!root_ || every_ <= 0 || el - last_ < every_ || step == 0) return;
    last_ = el;
    std::fprintf(stderr, "[gphr] %s: step %ld/%ld (t = %.4g), %.1f s elapsed, ~%.1f s left\n", label_.c_str(),
                 step, total_, t, el, el / step * (total_ - step));
  }

 private:
  std::string label_;
  long total_;
  double every_, last_ = 0.0;
  bool root_;
  Teuchos::Time clock_;
};
}  // namespace

double maxDeviation(const std::vector<double>& H, double H0) {
  double d = 0.0;
  for (double h : H) d = std::max(d, std::abs(h - H0));
  return d;
}

double driftBound(const Teuchos::ParameterList& integrator, int degree, const RunStats& stats) {
  return quadratureIsExact(integrator.get<std::string>("scheme"), integrator.get<int>("quadraturePoints"), degree)
             ? stats.driftBound
             : std::numeric_limits<double>::quiet_NaN();
}

EvaluationSettings evaluationSettingsFrom(const Teuchos::ParameterList& cfg) {
  EvaluationSettings s;
  s.time.dt = cfg.sublist("time").get<double>("dt");
  s.time.steps = numSteps(cfg);
  s.time.integrator = cfg.sublist("integrator");
  s.saveEvery = cfg.sublist("output").get<int>("saveEvery");
  s.progressSeconds = cfg.sublist("output").get<double>("progressSeconds");
  s.onlineRepeats = cfg.sublist("pipeline").get<int>("onlineRepeats");
  s.onlineRepeatSeconds = cfg.sublist("pipeline").get<double>("onlineRepeatSeconds");
  s.shift = cfg.sublist("scene").get<bool>("shift");
  if (cfg.sublist("output").get<bool>("plots") || cfg.sublist("output").get<bool>("xdmf"))
    s.fieldModels = fieldModelNames(cfg);
  return s;
}

FomResult runFullModel(const EvaluationSettings& settings, const Scene& scene, const std::vector<double>& mu,
                       const RCP<const Comm>& comm) {
  const long steps = settings.time.steps, saveEvery = settings.saveEvery;
  const double dt = settings.time.dt;
  auto inst = scene.instantiate(comm, mu, settings.shift);
  FullModelIntegrator integ(inst.system, settings.time.integrator);

  FomResult res;
  const long numSaved = steps / saveEvery + 1 + (steps % saveEvery != 0);
  res.trajectory = rcp(new MultiVector(inst.system->map(), numSaved));
  res.hamiltonian.reserve(steps + 1);
  Vector y(*inst.y0, Teuchos::Copy);
  const auto ref = inst.system->reference();
  Progress progress(method::kFom, steps, settings.progressSeconds, comm->getRank() == 0);
  long saved = 0;
  const std::function<void(long, double, const Vector&)> observe = [&](long j, double t, const Vector& yj) {
    res.hamiltonian.push_back(finiteHamiltonian(inst.system->hamiltonian(yj), j));
    if (isSavedStep(j, steps, saveEvery)) {
      auto col = res.trajectory->getVectorNonConst(saved++);
      if (ref.is_null()) Tpetra::deep_copy(*col, yj);
      else col->update(1.0, yj, 1.0, *ref, 0.0);
      res.savedTimes.push_back(t);
    }
    progress.update(j, t);
  };
  const SimulationStats sim = observedTimeLoop(integ, y, dt, steps, observe);
  // The full model is the reference: its failure is the run's error (exit 3), not a status.
  if (!sim.ok()) throw SolverError(sim.reason);
  const RunStats& stats = sim.run;

  const double H0 = res.hamiltonian.front(), herr = maxDeviation(res.hamiltonian, H0);
  res.tOnline = sim.onlineSeconds;
  res.metrics.set(Metric::Method, method::kFom)
      .set(Metric::N, static_cast<long>(inst.system->space().n()))
      .set(Metric::FullDim, static_cast<long>(inst.system->space().fullDim()))
      .set(Metric::NumTerms, static_cast<long>(inst.system->nonlinearTerm().numTerms()))
      .set(Metric::Steps, steps)
      .set(Metric::Dt, dt)
      .set(Metric::Ranks, comm->getSize())
      .set(Metric::TOnlineS, sim.onlineSeconds)
      .set(Metric::NewtonItersAvg, double(stats.newtonIterations) / steps)
      .set(Metric::LinearItersAvg, double(stats.linearIterations) / steps)
      .set(Metric::LinearItersPerNewton, stats.newtonIterations ? double(stats.linearIterations) / stats.newtonIterations : 0.0)
      .set(Metric::NewtonResidualMax, stats.maxResidual)
      .set(Metric::HDriftBound, driftBound(settings.time.integrator, inst.system->nonlinearTerm().polynomialDegree(), stats))
      .set(Metric::H0, H0)
      .set(Metric::HErrMax, herr)
      .set(Metric::HErrMaxRel, H0 != 0.0 ? herr / std::abs(H0) : herr)
      .set(Metric::Status, "ok");
  if (!settings.fieldModels.empty())
    res.fieldStates = std::make_shared<FieldStates>(settings.fieldModels, res.trajectory->getNumVectors());
  return res;
}

}  // namespace gphr
