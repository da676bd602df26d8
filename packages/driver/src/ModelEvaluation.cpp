#include "gphr/driver/ModelEvaluation.hpp"

#include <Teuchos_Time.hpp>
#include <algorithm>
#include <cmath>
#include <limits>

#include "gphr/core/Error.hpp"
#include "gphr/driver/Config.hpp"
#include "gphr/timeint/DenseModelIntegrator.hpp"

namespace gphr {

std::string ModelRun::label() const {
  return method + " k=" + std::to_string(k) + (m > 0 ? " m=" + std::to_string(m) : "");
}

std::vector<int> stageK(const Teuchos::ParameterList& cfg, const ReducedBasis& basis) {
  std::vector<int> ks;
  for (int k : pipelineK(cfg)) {
    if (k == 0) k = basis.k;
    GPHR_REQUIRE(k <= basis.k, InputError, "k = ", k, " is larger than the basis (k = ", basis.k, ")");
    ks.push_back(k);
  }
  return ks;
}

RCP<MultiVector> leadingBasis(const ReducedBasis& basis, int k) {
  const int kb = basis.k;
  if (k == kb) return basis.A;
  Teuchos::Array<size_t> cols;
  for (int j = 0; j < k; ++j) cols.push_back(j);
  for (int j = 0; j < k; ++j) cols.push_back(kb + j);
  return rcp(new MultiVector(*basis.A->subCopy(cols())));
}

namespace {
// The report's per-step diagnostics of a reduced trajectory: the true Hamiltonian H(y0 + A z^j)
// at every step and the error against the FOM at the saved steps. The reduced states are lifted
// in batches, A [z^j ... z^{j+B-1}] as one GEMM, after the steps: lifting one state per step
// (a GEMV with the n x 2k basis) streamed the whole basis through the caches between two time
// steps, which slowed the small model's own stepping (its L_r, LU and basis rows were evicted)
// and so inflated t_online, and a GEMM lifts faster than B GEMVs. B keeps the batch under
// ~64 MB of lifted states.
class BatchedLift {
 public:
  BatchedLift(const MultiVector& A, const HamiltonianSystem& sys, const FomResult& fom, long steps, long saveEvery,
              bool keepStates, ModelRun& run)
      : A_(A), sys_(sys), fom_(fom), steps_(steps), saveEvery_(saveEvery), keepStates_(keepStates), run_(run) {
    const size_t d = std::max<size_t>(1, A.getGlobalLength());
    batch_ = static_cast<int>(std::clamp<size_t>((size_t(8) << 20) / d, 1, 64));
    const auto local = rcp(new Map(A.getNumVectors(), 0, A.getMap()->getComm(), Tpetra::LocallyReplicated));
    Z_ = rcp(new MultiVector(local, batch_));
    Y_ = rcp(new MultiVector(A.getMap(), batch_));
  }
  void add(long step, const DenseVector& z) {
    {
      auto v = Z_->getLocalViewHost(Tpetra::Access::ReadWrite);
      for (int i = 0; i < z.length(); ++i) v(i, count_) = z(i);
    }
    steps_of_[count_++] = step;
    if (count_ == batch_) flush();
  }
  void flush() {
    if (count_ == 0) return;
    Y_->multiply(Teuchos::NO_TRANS, Teuchos::NO_TRANS, 1.0, A_, *Z_, 0.0);
    const auto ref = sys_.reference();
    for (int c = 0; c < count_; ++c) {
      const RCP<Vector> y = Y_->getVectorNonConst(c);
      run_.hamiltonian.push_back(sys_.hamiltonian(*y));  // H_s(A z) = H(y0 + A z)
      if (!isSavedStep(steps_of_[c], steps_, saveEvery_)) continue;
      if (!ref.is_null()) y->update(1.0, *ref, 1.0);  // physical state y0 + A z
      if (keepStates_) run_.states.push_back(rcp(new Vector(*y, Teuchos::Copy)));
      const auto yf = fom_.trajectory->getVector(saved_++);
      y->update(-1.0, *yf, 1.0);
      const double e = y->norm2(), nf = yf->norm2();
      num_ += e * e;
      den_ += nf * nf;
      final_ = e / nf;
      run_.errors.push_back(e);
    }
    count_ = 0;
  }
  double relativeL2() const { return std::sqrt(num_ / den_); }
  double finalError() const { return final_; }

 private:
  const MultiVector& A_;
  const HamiltonianSystem& sys_;
  const FomResult& fom_;
  long steps_, saveEvery_;
  bool keepStates_;
  ModelRun& run_;
  int batch_ = 1, count_ = 0;
  long steps_of_[64] = {};
  long saved_ = 0;
  double num_ = 0.0, den_ = 0.0, final_ = 0.0;
  RCP<MultiVector> Z_, Y_;
};
}  // namespace

ModelRun evaluateReducedModel(const RunContext& ctx, const FomResult& fom, const HamiltonianSystem& sys,
                              const MultiVector& A, DenseHamiltonian& model, bool hasHamiltonian,
                              const std::string& method, int k, int m, bool keepStates,
                              const AfterStepHook& afterStep) {
  const long steps = numSteps(ctx.config), saveEvery = ctx.config.sublist("output").get<int>("saveEvery");
  const double dt = ctx.config.sublist("time").get<double>("dt");
  ModelRun run;
  run.method = method, run.k = k, run.m = m;
  DenseModelIntegrator integ(model, ctx.config.sublist("integrator"), sys.nonlinearTerm().polynomialDegree());
  DenseVector z(model.dim());
  BatchedLift lift(A, sys, fom, steps, saveEvery, keepStates, run);
  double obsSeconds = 0.0;
  long lastStep = 0;
  Teuchos::Time wall("model"), obs("obs");
  std::string status = "ok", why;
  RunStats stats;
  wall.start();
  try {
    stats = integ.run(z, dt, steps, [&](long j, double, const DenseVector& zj, const StepReport&) {
      obs.start(true);
      lastStep = j;
      for (int i = 0; i < zj.length(); ++i)
        GPHR_REQUIRE(std::isfinite(zj(i)), SolverError, "non-finite reduced state at step ", j);
      if (hasHamiltonian) run.modelHamiltonian.push_back(model.hamiltonian(zj));  // the model at this step
      lift.add(j, zj);
      obsSeconds += obs.stop();
      if (afterStep) afterStep(j, zj);
    });
  } catch (const SolverError& e) {
    status = "diverged";
    why = e.what();
    run.ok = false;
    if (obs.isRunning()) obsSeconds += obs.stop();
  }
  const double total = wall.stop();
  lift.flush();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double H0 = fom.hamiltonian.front(), herr = run.ok ? maxDeviation(run.hamiltonian, H0) : nan;
  run.eL2 = run.ok ? lift.relativeL2() : nan;
  run.tOnline = total - obsSeconds;
  run.run.set("method", method).set("k", static_cast<long>(k)).set("reducedDim", static_cast<long>(2 * k));
  if (m > 0) run.run.set("m", static_cast<long>(m));
  run.run.set("steps", steps)
      .set("E_L2", run.eL2)
      .set("E_fin", run.ok ? lift.finalError() : nan)
      .set("H_err_max", herr)
      .set("H_err_final", run.ok && !run.hamiltonian.empty() ? std::abs(fom.hamiltonian.back() - run.hamiltonian.back()) : nan)
      .set("H_err_max_rel", H0 != 0.0 ? herr / std::abs(H0) : herr)
      .set("t_online_s", run.tOnline)
      .set("newton_iters_avg", run.ok ? double(stats.newtonIterations) / steps : nan)
      .set("newton_matrices", run.ok ? stats.newtonMatrices : -1L)
      .set("errors_at", "saved steps (every output.saveEvery-th and the last)")
      .set("status", status);
  if (hasHamiltonian && run.ok) run.run.set("H_model_err_max", maxDeviation(run.modelHamiltonian, run.modelHamiltonian.front()));
  if (!run.ok) run.run.set("diverged_at_step", lastStep + 1).set("diverged_reason", why);
  if (!run.ok && ctx.comm->getRank() == 0)
    std::fprintf(stderr, "[gphr] %s diverged at step %ld: %s\n", run.label().c_str(), lastStep + 1, why.c_str());
  return run;
}

}  // namespace gphr
