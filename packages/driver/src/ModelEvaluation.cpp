#include "gphr/driver/ModelEvaluation.hpp"

#include <Teuchos_Time.hpp>
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
// y = A z on the state map; the replicated z buffer is allocated once.
class Lift {
 public:
  explicit Lift(const MultiVector& A)
      : A_(A), z_(rcp(new Map(A.getNumVectors(), 0, A.getMap()->getComm(), Tpetra::LocallyReplicated)), 1) {}
  void operator()(const DenseVector& z, Vector& y) {
    {
      auto v = z_.getLocalViewHost(Tpetra::Access::OverwriteAll);
      for (int i = 0; i < z.length(); ++i) v(i, 0) = z(i);
    }
    y.multiply(Teuchos::NO_TRANS, Teuchos::NO_TRANS, 1.0, A_, z_, 0.0);
  }

 private:
  const MultiVector& A_;
  MultiVector z_;
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
  Vector y(sys.map());
  Lift lift(A);
  const auto ref = sys.reference();
  double num = 0.0, den = 0.0, fin = 0.0, obsSeconds = 0.0;
  long saved = 0, lastStep = 0;
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
      lift(zj, y);
      run.hamiltonian.push_back(sys.hamiltonian(y));  // H_s(A z) = H(y0 + A z)
      if (hasHamiltonian) run.modelHamiltonian.push_back(model.hamiltonian(zj));
      if (isSavedStep(j, steps, saveEvery)) {
        if (!ref.is_null()) y.update(1.0, *ref, 1.0);  // physical state y0 + A z
        if (keepStates) run.states.push_back(rcp(new Vector(y, Teuchos::Copy)));
        const auto yf = fom.trajectory->getVector(saved++);
        y.update(-1.0, *yf, 1.0);
        const double e = y.norm2(), nf = yf->norm2();
        num += e * e;
        den += nf * nf;
        fin = e / nf;
        run.errors.push_back(e);
      }
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
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double H0 = fom.hamiltonian.front(), herr = run.ok ? maxDeviation(run.hamiltonian, H0) : nan;
  run.eL2 = run.ok ? std::sqrt(num / den) : nan;
  run.tOnline = total - obsSeconds;
  run.run.set("method", method).set("k", static_cast<long>(k)).set("reducedDim", static_cast<long>(2 * k));
  if (m > 0) run.run.set("m", static_cast<long>(m));
  run.run.set("steps", steps)
      .set("E_L2", run.eL2)
      .set("E_fin", run.ok ? fin : nan)
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
