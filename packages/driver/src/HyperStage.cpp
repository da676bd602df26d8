#include "gphr/driver/HyperStage.hpp"

#include <Teuchos_Time.hpp>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "gphr/core/Error.hpp"
#include "gphr/core/Progress.hpp"
#include "gphr/driver/ModelEvaluation.hpp"
#include "gphr/hyper/DeimBasis.hpp"
#include "gphr/hyper/EmpiricalQuadrature.hpp"
#include "gphr/hyper/GpAdeimModel.hpp"
#include "gphr/hyper/GpDeimModel.hpp"
#include "gphr/hyper/GradientDeimModel.hpp"
#include "gphr/reduction/Deim.hpp"
#include "gphr/offline/TermWeightFits.hpp"
#include "gphr/reduction/GalerkinRom.hpp"
#include "gphr/core/Method.hpp"

namespace gphr {

namespace {

bool wants(const std::vector<std::string>& methods, const char* m) {
  return std::find(methods.begin(), methods.end(), m) != methods.end();
}

ModelRun unavailable(const std::string& method, int k, int m, const std::string& why) {
  ModelRun r;
  r.method = method, r.k = k, r.m = m, r.ok = false, r.available = false;
  // not run: its error and times stay NaN (ReducedEvaluation::kNotMeasured), never 0
  r.metrics.set(Metric::Reason, why);
  return r;
}

// The reduced model's smallest Hessian eigenvalue at z0 = 0: the convexity reference of the
// term-weighted models (gp-deim, gp-eqp).
double romHessianMinEig(const SceneInstance& inst, const MultiVector& A, int k) {
  GalerkinRom rom(inst.system, rcp(new MultiVector(A, Teuchos::Copy)));
  DenseMatrix Hr(2 * k, 2 * k);
  rom.addHessian(DenseVector(2 * k), 1.0, Hr);
  return smallestEigenvalue(Hr);
}

// A term-weighted model (GpDeimModel on a sample mesh: DEIM or quadrature weights) evaluated like
// the reduced model, with the diagnostics they share: Hess H_hr(z0)'s smallest eigenvalue beside
// the reduced model's, whether convexity was lost, and the online size.
ModelRun evaluateTermModel(const RunOptions& opt, const FomResult& fom, const SceneInstance& inst, const MultiVector& A,
                           GpDeimModel& model, const std::string& method, int k, int m, double lminR) {
  DenseMatrix Hhr(2 * k, 2 * k);
  model.addHessian(DenseVector(2 * k), 1.0, Hhr);
  const double lminHr = smallestEigenvalue(Hhr);
  ModelRun run = evaluateRun(opt.evaluation, fom, *inst.system, A, model, {method, k, m, {}});
  run.metrics.set(Metric::HessMinEigHr, lminHr)
      .set(Metric::HessMinEigRom, lminR)
      .set(Metric::ConvexityLost, lminHr < 0.0 && lminR >= 0.0)
      .set(Metric::KernelRowsPerEvaluation, static_cast<long>(model.kernelRowsPerEvaluation()))
      .set(Metric::OnlineNumbersHeld, static_cast<long>(model.numbersHeld()));
  return run;
}

void runGpDeim(const RunOptions& opt, const FomResult& fom, RomStages& st, const SceneInstance& inst,
               const MultiVector& A, int k, const ReducedLinearPart& linear) {
  const CachedDeimBasis& db = st.offline->deimBasis(k);
  if (k == st.offline->sizes().back()) st.deimSingularValues = db.basis.singularValues;
  const double lminR = romHessianMinEig(inst, A, k);
  for (int m : opt.pipeline.msOf(k)) {
    if (m > static_cast<int>(db.basis.U->getNumVectors())) {
      st.runs.push_back(unavailable(method::kGpDeim, k, m, "the DEIM basis has " + std::to_string(db.basis.U->getNumVectors()) +
                                                         " vectors (numerical rank of the snapshots or hyper.maxRank)"));
      continue;
    }
    Teuchos::Time clock("deim pair");
    clock.start();
    DeimWeights w;
    auto hr = buildGpDeimModel(*inst.system, A, *db.basis.U, m, opt.indices, &w, &linear);
    const double tPair = clock.stop();
    ModelRun run = evaluateTermModel(opt, fom, inst, A, *hr, method::kGpDeim, k, m, lminR);
    run.metrics.set(Metric::CondPtU, w.conditionNumber)
        .set(Metric::DeimWeightMin, *std::min_element(w.weights.begin(), w.weights.end()))
        .set(Metric::DeimWeightMax, *std::max_element(w.weights.begin(), w.weights.end()))
        .set(Metric::DeimBasisCached, db.cached)
        .set(Metric::DeimPodStepsTsqr, static_cast<long>(db.basis.podSteps.tsqr))  // 0 when cached or randomized
        .set(Metric::DeimPodStepsStacked, static_cast<long>(db.basis.podSteps.stacked))
        .set(Metric::DeimPodStepsReplicated, static_cast<long>(db.basis.podSteps.replicated))
        .set(Metric::DeimPodStepsTree, static_cast<long>(db.basis.podSteps.tree))
        .set(Metric::TDeimBasisS, db.seconds)
        .set(Metric::TDeimPairS, tPair)
        .set(Metric::TOfflineS, st.training.seconds + st.basisSeconds + db.seconds + tPair)
        .set(Metric::TDeimBasisComputeS, db.computeSeconds)
        .set(Metric::THyperOfflineS, db.computeSeconds + tPair)
        .set(Metric::TTotalS, db.computeSeconds + tPair + run.tOnline);
    setBasisKeys(opt, st, run.metrics);
    st.runs.push_back(std::move(run));
  }
}

// gp-eqp (NNLS terms and weights, pipeline.m the term budget) or gp-eqp-refit (GP-DEIM's terms,
// least-squares weights) for every m: the fit, then GpDeimModel on its sample mesh.
void runGpEqp(const RunOptions& opt, const FomResult& fom, RomStages& st, const SceneInstance& inst,
              const MultiVector& A, int k, const ReducedLinearPart& linear, const std::string& method) {
  TermWeightFits& fits = st.offline->termWeightFits(k, opt.indices);
  const double lminR = romHessianMinEig(inst, A, k);
  for (int m : opt.pipeline.msOf(k)) {
    CachedFit c;
    try {
      c = fits.get(method, m);
    } catch (const InputError& e) {  // a budget the training cannot support: that run is unavailable
      st.runs.push_back(unavailable(method, k, m, e.what()));
      continue;
    }
    Teuchos::Time clock("eqp mesh");
    clock.start();
    auto hr = buildQuadratureModel(*inst.system, A, c.fit, linear);
    const double tMesh = clock.stop();
    ModelRun run = evaluateTermModel(opt, fom, inst, A, *hr, method, k, m, lminR);
    const auto [wmin, wmax] = std::minmax_element(c.fit.weights.begin(), c.fit.weights.end());
    const double offline = c.trainingSeconds + c.fitSeconds + tMesh;
    run.metrics.set(Metric::EqpTerms, static_cast<long>(c.fit.terms.size()))
        .set(Metric::EqpFitResidual, c.fit.residual)
        .set(Metric::EqpFitResidualExactRows, c.exactResidual)
        .set(Metric::EqpWeightMin, *wmin)
        .set(Metric::EqpWeightMax, *wmax)
        .set(Metric::EqpStop, c.fit.stop)
        .set(Metric::EqpSelections, static_cast<long>(c.fit.iterations))
        .set(Metric::EqpCached, c.cached)
        .set(Metric::TEqpTrainingS, c.trainingSeconds)
        .set(Metric::TEqpFitS, c.fitSeconds)
        .set(Metric::TEqpMeshS, tMesh)
        .set(Metric::TOfflineS, st.training.seconds + st.basisSeconds + offline)
        .set(Metric::THyperOfflineS, offline)
        .set(Metric::TTotalS, offline + run.tOnline);
    setBasisKeys(opt, st, run.metrics);
    st.runs.push_back(std::move(run));
  }
}

// The largest drift of a local H_hr^j over its interval [ell_j, ell_{j+1}] (prop:ham_cons_adapt):
// modelHamiltonian[tau] is H_hr^j(z^tau) of the model that produced step tau; each interval
// starts from the record's H_hr^{j+1}(z^{ell_{j+1}}).
double localHamiltonianDrift(const ModelRun& run) {
  const auto& H = run.modelHamiltonian;
  double start = H.empty() ? 0.0 : H.front(), worst = 0.0;
  size_t next = 0;
  for (size_t tau = 1; tau < H.size(); ++tau) {
    worst = std::max(worst, std::abs(H[tau] - start));
    if (next < run.adeimUpdates.size() && run.adeimUpdates[next].step == static_cast<long>(tau))
      start = run.adeimUpdates[next++].hrAfter;
  }
  return worst;
}

void setAdeimSummary(ModelRun& run, const AdeimOptions& o, double tInitial, double tPair) {
  // The means are over the updates that ran; the time counts the skipped ones' indicators too.
  double tUpdates = 0.0, rankSum = 0.0, samples = 0.0;
  long skipped = 0;
  for (const auto& u : run.adeimUpdates) {
    tUpdates += u.seconds;
    if (u.skipped) ++skipped;
    else rankSum += u.rank, samples += u.numSamples;
  }
  const long ran = static_cast<long>(run.adeimUpdates.size()) - skipped;
  const double n = std::max<long>(1, ran);
  run.metrics.set(Metric::Updates, ran)
      .set(Metric::UpdatesSkipped, skipped)
      .set(Metric::UpdateRankMean, rankSum / n)
      .set(Metric::NumSamplesMean, samples / n)
      .set(Metric::TUpdatesS, tUpdates)
      .set(Metric::InitialBasis, o.initialBasis)
      .set(Metric::Sampling, o.sampling)
      .set(Metric::Delta0, static_cast<long>(o.initialWindow))
      .set(Metric::Delta, static_cast<long>(o.updateEvery))
      .set(Metric::Window, static_cast<long>(o.window))
      .set(Metric::Gamma, static_cast<long>(o.resampleEvery))
      .set(Metric::TInitialBasisS, tInitial)
      .set(Metric::TDeimPairS, tPair)
      .set(Metric::THyperOfflineS, tInitial + tPair)
      .set(Metric::TTotalS, tInitial + tPair + run.tOnline);
  if (run.ok) run.modelHamiltonianDrift = localHamiltonianDrift(run);
}

// GP-ADEIM (alg:SP-ADEIM) for every m: (U_0, P_0) from the first delta0 full-model steps at the
// test parameter (or the training DEIM basis), then the adaptive model evaluated like the others,
// its update records kept for adeim_updates.csv.
void runGpAdeim(const RunOptions& opt, const FomResult& fom, RomStages& st, const SceneInstance& inst,
                const RCP<const MultiVector>& A, int k, const ReducedLinearPart& linear) {
  const SimulationSettings& time = opt.evaluation.time;
  for (int m : opt.pipeline.msOf(k)) {
    const AdeimOptions o = adeimOptionsFor(opt.adeim, m);
    Teuchos::Time clock("adeim offline");
    clock.start();
    RCP<const MultiVector> U0;
    if (o.initialBasis == "fom") {
      try {  // too few directions in the first delta0 steps for this m: that run is unavailable
        U0 = initialAdeimBasis(inst.system, *inst.y0, *A, time.integrator, time.dt, o.initialWindow, m);
      } catch (const InputError& e) {
        st.runs.push_back(unavailable(method::kGpAdeim, k, m, e.what()));
        continue;
      }
    } else {
      U0 = st.offline->deimBasis(k).basis.U;
      if (m > static_cast<int>(U0->getNumVectors())) {
        st.runs.push_back(unavailable(method::kGpAdeim, k, m, "the training DEIM basis has " +
                                                            std::to_string(U0->getNumVectors()) + " vectors"));
        continue;
      }
    }
    const double tInitial = clock.stop();
    clock.start(true);
    GpAdeimModel model(inst.system, A, *U0, m, linear, o);
    const double tPair = clock.stop();
    // The lagged Newton matrix of the previous local model is kept across an update: it is a
    // Jacobian approximation like any lagged one, and the lag rule refactors when Newton slows
    // (resetting it at every update cost 600 LU factorisations instead of 143 on the NLS benchmark).
    const StepHook hook = adeimUpdateHook(model);
    ModelRun run = evaluateRun(opt.evaluation, fom, *inst.system, *A, model, {method::kGpAdeim, k, m, hook});
    run.adeimUpdates = model.updates();
    setAdeimSummary(run, o, tInitial, tPair);
    st.runs.push_back(std::move(run));
  }
}

// Classic DEIM (U_g from grad N snapshots) for every m, and SDEIM (U_g = A, m = 2k).
void runGradientDeim(const RunOptions& opt, const FomResult& fom, RomStages& st, const SceneInstance& inst,
                     const MultiVector& A, int k, const ReducedLinearPart& linear, bool classic, bool sdeim) {
  const auto& ms = opt.pipeline.msOf(k);
  const GradientSnapshots kind = opt.deimSnapshots;
  const std::string snapshots = kind == GradientSnapshots::Full ? "full" : "projected";
  auto evaluate = [&](const std::string& method, const MultiVector& Ug, int m, double tBasis) {
    Teuchos::Time clock("pair");
    clock.start();
    GradientDeimPair pair = makeGradientDeimPair(Ug, m, A);
    // The classic DEIM of full snapshots interpolates grad N - grad N(y0) (gradientDeimBasis):
    // grad N(y0) at the test parameter is added back. SDEIM interpolates grad N itself.
    const GradientBasis basis = methodInfo(method).gradientBasis;
    if (basis == GradientBasis::Snapshots && kind == GradientSnapshots::Full) pair = withReferenceGradient(std::move(pair), *inst.system, A);
    GradientDeimModel model(*inst.system, A, pair, linear);
    const double tPair = clock.stop();
    ModelRun run = evaluateRun(opt.evaluation, fom, *inst.system, A, model, {method, k, m, {}});
    run.metrics.set(Metric::KernelRowsPerEvaluation, static_cast<long>(model.kernelRowsPerEvaluation()))
        .set(Metric::TDeimBasisS, tBasis)
        .set(Metric::TDeimPairS, tPair)
        .set(Metric::DeimSnapshots, basis == GradientBasis::Snapshots ? snapshots : std::string("-"))
        .set(Metric::CondPtU, pair.conditionNumber)
        .set(Metric::TOfflineS, st.training.seconds + st.basisSeconds + tBasis + tPair);
    st.runs.push_back(std::move(run));
  };
  if (classic) {
    Teuchos::Time clock("gradient pod");
    clock.start();
    // the largest m with the DEIM basis's margin (hyper.maxRank is the reduced-Jacobian POD's)
    const int maxRank = *std::max_element(ms.begin(), ms.end()) + kDeimRankMargin;
    auto Ug = gradientDeimBasis(trainingSystems(*opt.scene, st.offline->comm(), st.training), st.training.snapshots, A,
                                maxRank, opt.offline.deim.snapshotEvery, kind);
    const double t = clock.stop();
    for (int m : ms) {
      if (m > static_cast<int>(Ug->getNumVectors())) {
        st.runs.push_back(unavailable(method::kDeim, k, m, "the gradient POD has " + std::to_string(Ug->getNumVectors()) +
                                                        " vectors"));
        continue;
      }
      evaluate(method::kDeim, *Ug, m, t);
    }
  }
  if (sdeim) evaluate(method::kSdeim, A, 2 * k, 0.0);
}

}  // namespace

void runHyperReduction(const RunOptions& opt, const FomResult& fom, RomStages& st) {
  const auto& methods = opt.pipeline.methods;
  const bool gp = wants(methods, method::kGpDeim), classic = wants(methods, method::kDeim), sd = wants(methods, method::kSdeim),
             adaptive = wants(methods, method::kGpAdeim), eqp = wants(methods, method::kGpEqp), refit = wants(methods, method::kGpEqpRefit);
  if (!gp && !classic && !sd && !adaptive && !eqp && !refit) return;
  const SceneInstance& inst = st.offline->instance();
  for (int k : st.offline->sizes()) {
    const auto A = st.offline->reducedBasis(k);
    const ProgressPhase phase("hyper-reduced models of k = " + std::to_string(k));
    const ReducedLinearPart linear = reduceLinearPart(*inst.system, *A);
    if (gp) runGpDeim(opt, fom, st, inst, *A, k, linear);
    if (eqp) runGpEqp(opt, fom, st, inst, *A, k, linear, method::kGpEqp);
    if (refit) runGpEqp(opt, fom, st, inst, *A, k, linear, method::kGpEqpRefit);
    if (adaptive) runGpAdeim(opt, fom, st, inst, A, k, linear);
    if (classic || sd) runGradientDeim(opt, fom, st, inst, *A, k, linear, classic, sd);
  }
}

}  // namespace gphr
