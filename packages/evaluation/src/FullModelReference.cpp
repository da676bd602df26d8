#include "gphr/evaluation/FullModelReference.hpp"

#include <Teuchos_Time.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gphr/core/Error.hpp"
#include "gphr/core/Progress.hpp"
#include "gphr/core/Method.hpp"
#include "gphr/timeint/FullModelIntegrator.hpp"

namespace gphr {

namespace {
// Progress on stderr (rank 0) at most every `every` seconds: step, time, elapsed, estimate left;
// the last step where the run took that long (a sequence of lines ends at N of N; a short run
// prints none).
class Progress {
 public:
  Progress(std::string label, long total, double every, bool root)
      : label_(std::move(label)), total_(total), every_(every), root_(root), clock_("progress") {
    clock_.start();
  }
  void update(long step, double t) {
    const double el = clock_.totalElapsedTime(true);
    if (!root_ || every_ <= 0 || step == 0 || el < every_ || (el - last_ < every_ && step < total_)) return;
    last_ = el;
    if (step == total_)
      progressLine("[gphr] %s: step %ld/%ld (t = %.4g), done in %.1f s", label_.c_str(), step, total_, t, el);
    else
      progressLine("[gphr] %s: step %ld/%ld (t = %.4g), %.1f s elapsed, ~%.1f s left", label_.c_str(), step, total_,
                   t, el, el / step * (total_ - step));
  }

 private:
  std::string label_;
  long total_;
  double every_, last_ = 0.0;
  bool root_;
  Teuchos::Time clock_;
};
}  // namespace

void setSizes(const HamiltonianSystem& system, FullModelReference& ref) {
  ref.n = system.space().n();
  ref.fullDim = system.space().fullDim();
  ref.numTerms = static_cast<long>(system.nonlinearTerm().numTerms());
}

double FullModelReference::maxStateNorm() const {
  std::vector<double> norms(trajectory->getNumVectors());
  trajectory->norm2(norms);
  return *std::max_element(norms.begin(), norms.end());
}

FullModelReference runFullModel(const EvaluationSettings& settings, const Scene& scene, const std::vector<double>& mu,
                                const RCP<const Comm>& comm) {
  const long steps = settings.time.steps, saveEvery = settings.saveEvery;
  auto inst = scene.instantiate(comm, mu, settings.shift);
  FullModelIntegrator integ(inst.system, settings.time.integrator);

  FullModelReference ref;
  ref.trajectory = rcp(new MultiVector(inst.system->map(), numSavedStates(steps, saveEvery)));
  ref.hamiltonian.reserve(steps + 1);
  Vector y(*inst.y0, Teuchos::Copy);
  const auto shiftBy = inst.system->reference();
  Progress progress(method::kFom, steps, settings.progressSeconds, comm->getRank() == 0);
  long saved = 0;
  const std::function<void(long, double, const Vector&)> observe = [&](long j, double t, const Vector& yj) {
    ref.hamiltonian.push_back(finiteHamiltonian(inst.system->hamiltonian(yj), j));
    if (isSavedStep(j, steps, saveEvery)) {
      auto col = ref.trajectory->getVectorNonConst(saved++);
      if (shiftBy.is_null()) Tpetra::deep_copy(*col, yj);
      else col->update(1.0, yj, 1.0, *shiftBy, 0.0);
      ref.savedTimes.push_back(t);
    }
    progress.update(j, t);
  };
  const SimulationStats sim = observedTimeLoop(integ, y, settings.time.dt, steps, observe);
  // The full model is the reference: its failure is the caller's error, not a status.
  if (!sim.ok()) throw SolverError(sim.reason);
  ref.stats = sim.run;
  ref.tOnline = sim.onlineSeconds;
  ref.driftBound = driftBound(settings.time, inst.system->nonlinearTerm().polynomialDegree(), sim.run);
  setSizes(*inst.system, ref);
  return ref;
}

}  // namespace gphr
