#include "gphr/driver/ModelEvaluation.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_Time.hpp>
#include <algorithm>
#include <cmath>
#include <limits>

#include "gphr/core/Error.hpp"
#include "gphr/driver/Config.hpp"
#include "gphr/driver/FieldModels.hpp"
#include "gphr/online/Lift.hpp"

namespace gphr {

std::string ModelRun::label() const {
  return method + " k=" + std::to_string(k) + (m > 0 ? " m=" + std::to_string(m) : "");
}

std::vector<int> stageK(const Teuchos::ParameterList& cfg, const ReducedBasis& basis) {
  return basisSizes(pipelineK(cfg), basis);
}

namespace {
// The report's per-step diagnostics of a reduced trajectory: the true Hamiltonian H(y0 + A z^j)
// at every step and the error against the FOM at the saved steps. The reduced states are kept
// (2k numbers a step, up to ~64 MB of them) and lifted after the time loop, A [z^j ...] in
// batches of B states as one GEMM. Lifting one state per step (a GEMV with the whole n x 2k
// basis) streamed the basis through the caches between two time steps, which evicted the small
// model's own data (L_r, its LU, the basis rows of the sample mesh) and so inflated t_online by
// an amount that grew with n; and a GEMM lifts faster than B GEMVs. B keeps the lifted batch
// under ~64 MB.
class DeferredLift {
 public:
  DeferredLift(const MultiVector& A, const HamiltonianSystem& sys, const FomResult& fom, long steps, long saveEvery,
               bool keepStates, ModelRun& run)
      : A_(A), sys_(sys), fom_(fom), steps_(steps), saveEvery_(saveEvery), keepStates_(keepStates), run_(run),
        r_(static_cast<int>(A.getNumVectors())) {
    const size_t d = std::max<size_t>(1, A.getGlobalLength()), budget = size_t(8) << 20;  // doubles
    batch_ = static_cast<int>(std::clamp<size_t>(budget / d, 1, 256));
    maxStored_ = std::max<size_t>(batch_, budget / std::max(1, r_));
    Z_ = liftWorkspace(A, batch_);
    Y_ = rcp(new MultiVector(A.getMap(), batch_));
  }
  void add(long step, const DenseVector& z) {
    stored_.insert(stored_.end(), z.values(), z.values() + r_);
    storedSteps_.push_back(step);
    if (storedSteps_.size() >= maxStored_) flush();
  }
  void flush() {
    for (size_t c0 = 0; c0 < storedSteps_.size(); c0 += batch_) liftBatch(c0, std::min(storedSteps_.size(), c0 + batch_));
    stored_.clear();
    storedSteps_.clear();
  }
  double relativeL2() const { return std::sqrt(num_ / den_); }
  double finalError() const { return final_; }

 private:
  void liftBatch(size_t c0, size_t c1) {
    const int count = static_cast<int>(c1 - c0);
    liftStates(A_, nullptr, &stored_[c0 * r_], count, *Z_, *Y_);  // A z: H_s(A z) before the shift is added
    const auto ref = sys_.reference();
    for (int c = 0; c < count; ++c) {
      const RCP<Vector> y = Y_->getVectorNonConst(c);
      run_.hamiltonian.push_back(sys_.hamiltonian(*y));  // H_s(A z) = H(y0 + A z)
      if (!ref.is_null()) y->update(1.0, *ref, 1.0);  // physical state y0 + A z
      run_.stateNorms.push_back(y->norm2());
      if (!isSavedStep(storedSteps_[c0 + c], steps_, saveEvery_)) continue;
      if (keepStates_) run_.states.push_back(rcp(new Vector(*y, Teuchos::Copy)));
      const auto yf = fom_.trajectory->getVector(saved_++);
      y->update(-1.0, *yf, 1.0);
      const double e = y->norm2(), nf = yf->norm2();
      num_ += e * e;
      den_ += nf * nf;
      final_ = e / nf;
      run_.errors.push_back(e);
    }
  }
  const MultiVector& A_;
  const HamiltonianSystem& sys_;
  const FomResult& fom_;
  long steps_, saveEvery_;
  bool keepStates_;
  ModelRun& run_;
  int r_, batch_ = 1;
  size_t maxStored_ = 1;
  std::vector<double> stored_;
  std::vector<long> storedSteps_;
  long saved_ = 0;
  double num_ = 0.0, den_ = 0.0, final_ = 0.0;
  RCP<MultiVector> Z_, Y_;
};
// The first step where a finished run's lift left the full model's range (RunStatus.hpp).
UnboundedStep unboundedStepOf(const FomResult& fom, const ModelRun& run) {
  std::vector<double> fomNorms(fom.trajectory->getNumVectors());
  fom.trajectory->norm2(fomNorms);
  return firstUnboundedStep(fom.hamiltonian.front(), *std::max_element(fomNorms.begin(), fomNorms.end()),
                            run.hamiltonian, run.stateNorms);
}
}  // namespace

ModelRun evaluateReducedModel(const RCP<const Comm>& comm, const EvaluationSettings& evaluation, const FomResult& fom,
                              const HamiltonianSystem& sys, const MultiVector& A, DenseHamiltonian& model,
                              bool hasHamiltonian, const std::string& method, int k, int m, bool keepStates,
                              const StepHook& adapt) {
  const long steps = evaluation.time.steps, saveEvery = evaluation.saveEvery;
  ModelRun run;
  run.method = method, run.k = k, run.m = m;
  SimulationSettings settings = evaluation.time;
  settings.polynomialDegree = sys.nonlinearTerm().polynomialDegree();
  DenseVector z;
  const bool fieldStates = fom.fieldStates && fom.fieldStates->wants(method);
  DeferredLift lift(A, sys, fom, steps, saveEvery, keepStates || fieldStates, run);
  const SimulationStats sim = simulate(model, settings, z, [&](long j, double, const DenseVector& zj) {
    if (hasHamiltonian) run.modelHamiltonian.push_back(finiteHamiltonian(model.hamiltonian(zj), j));  // the model at this step
    lift.add(j, zj);
  }, adapt);
  const RunStats& stats = sim.run;
  run.ok = sim.ok();
  const std::string& why = sim.reason;
  const long lastStep = sim.lastStep;
  lift.flush();
  run.tOnline = sim.onlineSeconds;
  // pipeline.onlineRepeats: the same online run again, timed only (a model that changes as it
  // runs, with an after-step hook, is not repeatable); t_online_s is the fastest.
  // pipeline.onlineRepeatSeconds caps the repeats' total time: on a shared machine a few-ms run's
  // time swings 2x over spells of tens of ms, so short runs need many repeats, long ones none.
  const int repeats = adapt ? 1 : evaluation.onlineRepeats;
  const double budget = evaluation.onlineRepeatSeconds;
  std::vector<double> times{run.tOnline};
  double spent = 0.0;
  for (int r = 1; r < repeats && run.ok && spent < budget; ++r) {
    times.push_back(simulate(model, settings, z).onlineSeconds);  // from z = 0 again, unobserved
    // The ranks decide together: a ROM repeat has collectives, so all ranks must run it or none.
    const double mine = spent + times.back();
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, mine, Teuchos::outArg(spent));
  }
  run.tOnline = *std::min_element(times.begin(), times.end());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double H0 = fom.hamiltonian.front(), herr = run.ok ? maxDeviation(run.hamiltonian, H0) : nan;
  run.eL2 = run.ok ? lift.relativeL2() : nan;
  run.metrics.set(Metric::Method, method).set(Metric::K, static_cast<long>(k)).set(Metric::ReducedDim, static_cast<long>(2 * k));
  if (m > 0) run.metrics.set(Metric::M, static_cast<long>(m));
  run.metrics.set(Metric::Steps, steps)
      .set(Metric::EL2, run.eL2)
      .set(Metric::EFin, run.ok ? lift.finalError() : nan)
      .set(Metric::HErrMax, herr)
      .set(Metric::HErrFinal, run.ok && !run.hamiltonian.empty() ? std::abs(fom.hamiltonian.back() - run.hamiltonian.back()) : nan)
      .set(Metric::HErrMaxRel, H0 != 0.0 ? herr / std::abs(H0) : herr)
      .set(Metric::TOnlineS, run.tOnline)
      .set(Metric::TOnlineRunsS, times)
      .set(Metric::NewtonItersAvg, run.ok ? double(stats.newtonIterations) / steps : nan)
      .set(Metric::NewtonMatrices, run.ok ? stats.newtonMatrices : -1L)
      .set(Metric::HDriftBound, run.ok ? driftBound(settings.integrator, settings.polynomialDegree, stats) : nan)
      .set(Metric::ErrorsAt, "saved steps (every output.saveEvery-th and the last)");
  if (run.ok) {
    const UnboundedStep u = unboundedStepOf(fom, run);
    run.unboundedAt = u.step, run.unboundedReason = u.reason;
  }
  if (run.unboundedAt >= 0) {
    run.metrics.set(Metric::UnboundedAtStep, run.unboundedAt).set(Metric::UnboundedReason, run.unboundedReason);
    if (comm->getRank() == 0)
      std::fprintf(stderr, "[gphr] %s unbounded from step %ld: %s\n", run.label().c_str(), run.unboundedAt,
                   run.unboundedReason.c_str());
  }
  run.metrics.set(Metric::Status, statusName(run.status()));
  if (hasHamiltonian && run.ok) run.metrics.set(Metric::HModelErrMax, maxDeviation(run.modelHamiltonian, run.modelHamiltonian.front()));
  if (!run.ok) run.metrics.set(Metric::DivergedAtStep, lastStep + 1).set(Metric::DivergedReason, why);
  if (!run.ok && comm->getRank() == 0)
    std::fprintf(stderr, "[gphr] %s diverged at step %ld: %s\n", run.label().c_str(), lastStep + 1, why.c_str());
  // The states go to the field outputs, which keep them only while this run is the most accurate
  // of a name of output.fieldModels; nothing else reads them.
  if (fieldStates) fom.fieldStates->offer(run);
  run.states.clear();
  return run;
}

}  // namespace gphr
