#include "gphr/evaluation/ReducedEvaluation.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>

#include "gphr/core/Progress.hpp"
#include "gphr/online/Lift.hpp"
#include "gphr/timeint/SchemeResidual.hpp"

namespace gphr {

namespace {
// The per-step diagnostics of a reduced trajectory: the true Hamiltonian H(y0 + A z^j) at every
// step and the error against the reference at the saved steps. The reduced states are kept (2k
// numbers a step, up to ~64 MB of them) and lifted after the time loop, A [z^j ...] in batches of
// B states as one GEMM. Lifting one state per step (a GEMV with the whole n x 2k basis) streamed
// the basis through the caches between two time steps, which evicted the small model's own data
// (L_r, its LU, the basis rows of the sample mesh) and so inflated t_online by an amount that grew
// with n; and a GEMM lifts faster than B GEMVs. B keeps the lifted batch under ~64 MB.
class DeferredLift {
 public:
  /// residual: the full scheme of the error indicator, or null; dt its step.
  DeferredLift(const MultiVector& A, const HamiltonianSystem& sys, const FullModelReference& ref, long steps,
               long saveEvery, bool keepStates, ReducedEvaluation& run, SchemeResidual* residual, double dt)
      : A_(A), sys_(sys), ref_(ref), steps_(steps), saveEvery_(saveEvery), keepStates_(keepStates), run_(run),
        r_(static_cast<int>(A.getNumVectors())), residual_(residual), dt_(dt) {
    const size_t d = std::max<size_t>(1, A.getGlobalLength()), budget = size_t(8) << 20;  // doubles
    batch_ = static_cast<int>(std::clamp<size_t>(budget / d, 1, 256));
    maxStored_ = std::max<size_t>(batch_, budget / std::max(1, r_));
    Z_ = liftWorkspace(A, batch_);
    Y_ = rcp(new MultiVector(A.getMap(), batch_));
    if (residual_) previous_ = rcp(new Vector(A.getMap())), error_ = rcp(new Vector(A.getMap()));
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
  double relativeL2() const { return std::sqrt(num_ / den_); }  // eq:errNR
  // eq:errNR with the estimated errors over the lift's norms.
  double estimatedRelativeL2() const {
    return indicatorFailed_ ? std::numeric_limits<double>::quiet_NaN() : std::sqrt(estimateNum_ / estimateDen_);
  }
  double finalError() const { return final_; }

 private:
  void liftBatch(size_t c0, size_t c1) {
    const int count = static_cast<int>(c1 - c0);
    liftStates(A_, nullptr, &stored_[c0 * r_], count, *Z_, *Y_);  // A z: H_s(A z) before the shift is added
    const auto shiftBy = sys_.reference();
    for (int c = 0; c < count; ++c) {
      const RCP<Vector> y = Y_->getVectorNonConst(c);
      run_.hamiltonian.push_back(sys_.hamiltonian(*y));  // H_s(A z) = H(y0 + A z)
      if (residual_) indicate(storedSteps_[c0 + c], *y);
      if (!shiftBy.is_null()) y->update(1.0, *shiftBy, 1.0);  // physical state y0 + A z
      run_.stateNorms.push_back(y->norm2());
      if (!isSavedStep(storedSteps_[c0 + c], steps_, saveEvery_)) continue;
      if (residual_) {
        estimateNum_ += estimatedError_ * estimatedError_;
        estimateDen_ += run_.stateNorms.back() * run_.stateNorms.back();
      }
      if (keepStates_) run_.states.push_back(rcp(new Vector(*y, Teuchos::Copy)));
      const auto yf = ref_.trajectory->getVector(saved_++);
      y->update(-1.0, *yf, 1.0);
      const double e = y->norm2(), nf = yf->norm2();
      num_ += e * e;
      den_ += nf * nf;
      final_ = e / nf;
      run_.errors.push_back(e);
    }
  }
  // The error of the lift at step j (shifted states), carried from step j - 1 by the full scheme's
  // linearised error equation with the scheme's residual at the lifted step as its source
  // (SchemeResidual::propagateError, doc/error-estimate.md). Error 0 at step 0: the lift starts at y0.
  // A lift far outside the full model's range (a run that blew up) can leave the error equation's
  // linear solve unconverged: the run then has no estimate (NaN), never an error of its own. The
  // solve's convergence is a global verdict, so every rank stops alike.
  void indicate(long step, const Vector& y) {
    if (step > 0 && !indicatorFailed_) {
      try {
        residual_->propagateError(*previous_, y, dt_, *error_);
        run_.estimatedErrors.push_back(error_->norm2());
        estimatedError_ = run_.estimatedErrors.back();
      } catch (const SolverError&) {
        indicatorFailed_ = true;
      }
    }
    previous_->assign(y);
  }
  const MultiVector& A_;
  const HamiltonianSystem& sys_;
  const FullModelReference& ref_;
  long steps_, saveEvery_;
  bool keepStates_;
  ReducedEvaluation& run_;
  int r_, batch_ = 1;
  size_t maxStored_ = 1;
  std::vector<double> stored_;
  std::vector<long> storedSteps_;
  long saved_ = 0;
  double num_ = 0.0, den_ = 0.0, final_ = 0.0;
  RCP<MultiVector> Z_, Y_;
  SchemeResidual* residual_;
  double dt_;
  RCP<Vector> previous_, error_;
  double estimatedError_ = 0.0, estimateNum_ = 0.0, estimateDen_ = 0.0;
  bool indicatorFailed_ = false;
};

// pipeline.onlineRepeats: the same online run again from z = 0, timed only (a model that changes
// as it runs, with an adaptive hook, is not repeatable); t_online is the fastest. The repeats'
// total time is capped: on a shared machine a few-ms run's time swings 2x over spells of tens of
// ms, so short runs need many repeats, long ones none. The ranks decide together: a ROM repeat
// has collectives, so all ranks must run it or none.
void timeRepeats(const EvaluationSettings& settings, const SimulationSettings& time, DenseHamiltonian& model,
                 const Comm& comm, ReducedEvaluation& run) {
  DenseVector z;
  double spent = 0.0;
  for (int r = 1; r < settings.onlineRepeats && run.ok && spent < settings.onlineRepeatSeconds; ++r) {
    run.onlineTimes.push_back(simulate(model, time, z).onlineSeconds);
    const double mine = spent + run.onlineTimes.back();
    Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, mine, Teuchos::outArg(spent));
  }
  run.tOnline = *std::min_element(run.onlineTimes.begin(), run.onlineTimes.end());
}
}  // namespace

ReducedEvaluation evaluateReducedModel(const EvaluationSettings& settings, const FullModelReference& reference,
                                       const HamiltonianSystem& system, const MultiVector& A, DenseHamiltonian& model,
                                       const ReducedRunOptions& options) {
  ReducedEvaluation run;
  SimulationSettings time = settings.time;
  time.polynomialDegree = system.nonlinearTerm().polynomialDegree();
  DenseVector z;
  std::unique_ptr<SchemeResidual> residual;
  if (settings.errorIndicator) residual = std::make_unique<SchemeResidual>(Teuchos::rcpFromRef(system), time.integrator);
  DeferredLift lift(A, system, reference, time.steps, settings.saveEvery, options.keepStates, run, residual.get(),
                    time.dt);
  const std::string label = options.label.empty() ? std::string("reduced model") : options.label;
  std::optional<ProgressPhase> phase(std::in_place, label + ": online run", time.steps);
  const SimulationStats sim = simulate(model, time, z, [&](long j, double, const DenseVector& zj) {
    if (options.hasHamiltonian) run.modelHamiltonian.push_back(finiteHamiltonian(model.hamiltonian(zj), j));
    lift.add(j, zj);
    phase->at(j);
  }, options.adapt);
  phase.emplace(label + ": errors and timing repeats");
  lift.flush();
  run.ok = sim.ok();
  run.lastStep = sim.lastStep;
  run.divergedReason = sim.reason;
  run.stats = sim.run;
  run.onlineTimes = {sim.onlineSeconds};
  if (!options.adapt) timeRepeats(settings, time, model, *A.getMap()->getComm(), run);
  else run.tOnline = sim.onlineSeconds;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  run.eL2 = run.ok ? lift.relativeL2() : nan;
  run.eFinal = run.ok ? lift.finalError() : nan;
  run.errorEstimate = run.ok && residual ? lift.estimatedRelativeL2() : nan;
  run.driftBound = run.ok ? driftBound(time, time.polynomialDegree, sim.run) : nan;
  const double H0 = reference.hamiltonian.front();
  run.hamiltonianErrorMax = run.ok ? maxDeviation(run.hamiltonian, H0) : nan;
  run.hamiltonianErrorMaxRelative = H0 != 0.0 ? run.hamiltonianErrorMax / std::abs(H0) : run.hamiltonianErrorMax;
  run.hamiltonianErrorFinal = run.ok && !run.hamiltonian.empty()
                                  ? std::abs(reference.hamiltonian.back() - run.hamiltonian.back())
                                  : nan;
  run.modelHamiltonianDrift = options.hasHamiltonian && run.ok
                                  ? maxDeviation(run.modelHamiltonian, run.modelHamiltonian.front())
                                  : nan;
  if (run.ok) {
    const UnboundedStep u =
        firstUnboundedStep(reference.hamiltonian.front(), reference.maxStateNorm(), run.hamiltonian, run.stateNorms);
    run.unboundedAt = u.step, run.unboundedReason = u.reason;
  }
  return run;
}

}  // namespace gphr
