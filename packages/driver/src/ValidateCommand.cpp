// `gphr validate MODEL.h5 TESTS.yaml --output DIR`: every model of the file, and the Galerkin ROM
// of each k, against the full model at each test point: the error over the parameter box, not at
// one point. The full model runs distributed over all ranks, one point after another, its saved
// states cached in DIR/fom/<point>.h5; each point's results are kept in DIR/points/<point>.txt
// (write-then-rename, keyed), so a killed run resumes without redoing finished points. The
// hyper-reduced models are loaded from the file as a query loads them (interpolated set-up unless
// the point asks for the exact one) and lifted with the stored basis for the error eq:errNR.
#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "gphr/core/Error.hpp"
#include "gphr/core/Progress.hpp"
#include "gphr/core/RankGroups.hpp"
#include "gphr/driver/ValidateCommand.hpp"
#include "gphr/driver/OutputDirectory.hpp"
#include "gphr/driver/Config.hpp"
#include "gphr/driver/ModelEvaluation.hpp"
#include "gphr/driver/OutputLock.hpp"
#include "gphr/driver/QueryList.hpp"
#include "gphr/driver/ValidationReport.hpp"
#include "gphr/evaluation/ReferenceCache.hpp"
#include "gphr/reduction/GalerkinRom.hpp"
#include "gphr/offline/Training.hpp"
#include "gphr/core/Method.hpp"

namespace gphr {

namespace {

// The point's evaluation: its T, dt and saveEvery with the file's integrator, one timing run per
// model, the shifted system (the file's models are of it).
EvaluationSettings pointSettings(const ReducedModel& rm, const Query& q) {
  EvaluationSettings s;
  s.time.dt = q.dt;
  s.time.steps = wholeSteps(q.T, q.dt);
  s.time.integrator = rm.integrator();
  s.saveEvery = q.saveEvery;
  s.onlineRepeats = 1;
  s.progressSeconds = 2.0;  // the full model's progress lines as gphr run's default (output.progressSeconds)
  s.shift = true;
  return s;
}

std::string fomKey(const Query& q, const ReducedModelData& d) {
  char buf[64];
  std::string s = d.sceneConfig + d.integratorConfig;
  for (double x : q.mu) std::snprintf(buf, sizeof buf, "mu=%.17g;", x), s += buf;
  std::snprintf(buf, sizeof buf, "T=%.17g;dt=%.17g;save=%ld", q.T, q.dt, q.saveEvery);
  return s + buf + ";gphr=" + gphrVersion();
}

// "validate: point 'NAME' (eps = 1e+08)": what a failure at a point names.
std::string pointName(const Query& q, const ReducedModelData& d) {
  std::string s = "validate: point '" + q.name + "' (";
  for (size_t j = 0; j < q.mu.size(); ++j)
    s += detail::concat(j ? ", " : "", j < d.parameterNames.size() ? d.parameterNames[j] : "mu", " = ", q.mu[j]);
  return s + ")";
}

// The full model at the point, from DIR/fom/<point>.h5 where it holds it under the point's key
// (the evaluation library's reference cache), else run and stored there.
FomResult fullModel(const RunContext& ctx, const ReducedModel& rm, const Query& q, const EvaluationSettings& settings,
                    bool& cached) {
  FullModelReference ref = cachedFullModel(ctx.outputDir + "/fom/" + q.name + ".h5", fomKey(q, rm.data()), settings,
                                           rm.scene(), q.mu, ctx.comm, &cached);
  return fomResultOf(std::move(ref), settings, ctx.comm->getSize());
}

// The full models of the points whose results are not in DIR/points, over rank groups
// (trainingGroupSize: a group per point, as many as the points' system size allows): group g runs
// points g, g + G, ... on its own ranks into DIR/fom/<point>.h5 (one file per point, so groups
// never share a writer); the points' evaluations then read them back on all ranks. The full
// model's time in the report is then its time on its group's ranks.
void fullModelsOverGroups(const RunContext& ctx, const ReducedModel& rm, const std::vector<Query>& points,
                          const std::vector<char>& reused) {
  const auto& d = rm.data();
  const long fullDim = rm.scene().instantiate(ctx.comm, points.front().mu, true).system->space().fullDim();
  const int size = trainingGroupSize(fullDim, ctx.comm->getSize(), static_cast<long>(points.size()));
  const int groups = ctx.comm->getSize() / size;
  if (groups < 2 || std::count(reused.begin(), reused.end(), 0) == 0) return;  // on all ranks, or nothing to run
  const int group = std::min(ctx.comm->getRank() / size, groups - 1);
  RunContext sub = ctx;
  sub.comm = ctx.comm->split(group, ctx.comm->getRank());
  GroupFailure failure;  // what this group's full models threw: agreed on below, so no group waits for it
  for (size_t i = group; i < points.size() && failure.text.empty(); i += groups) {
    if (reused[i]) continue;
    failure = failureOf(pointName(points[i], d), "the full model failed: ", [&] {
      bool cached = false;
      fullModel(sub, rm, points[i], pointSettings(rm, points[i]), cached);
    });
  }
  agreeOnFailure(*ctx.comm, failure);
  if (ctx.comm->getRank() == 0)
    std::fprintf(stderr, "[gphr] validate: full models in %d groups of %d rank(s)\n", groups, size);
}

ValidationRecord recordOf(const ModelRun& run, const Query& q, double setupSeconds, bool extrapolated) {
  ValidationRecord r;
  r.point = q.name, r.mu = q.mu, r.method = run.method, r.k = run.k, r.m = run.m;
  r.status = run.status(), r.eL2 = run.eL2, r.onlineSeconds = run.tOnline, r.setupSeconds = setupSeconds;
  r.errorEstimate = run.errorEstimate;
  r.extrapolated = extrapolated;
  return r;
}

// Every model at one point: the ROM of each k and each stored hyper-reduced model.
std::vector<ValidationRecord> evaluatePoint(RunContext& ctx, const ReducedModel& rm, const Query& q, double& tFom,
                                            bool& cached) {
  const auto& d = rm.data();
  const EvaluationSettings settings = pointSettings(rm, q);
  const auto inst = rm.scene().instantiate(ctx.comm, q.mu, true);
  FomResult fom;
  try {
    fom = fullModel(ctx, rm, q, settings, cached);
  } catch (const SolverError& e) {  // worded as over rank groups (fullModelsOverGroups)
    throw SolverError(detail::concat("the full model failed: ", e.what()));
  }
  tFom = fom.tOnline;
  const bool outside = d.outsideBox(q.mu);
  std::vector<ValidationRecord> out;
  for (const auto& b : d.bases) {
    const RCP<const MultiVector> A = rm.basis(b.k, inst.system->space());
    GalerkinRom rom(inst.system, A);
    out.push_back(recordOf(evaluateRun(settings, fom, *inst.system, *A, rom, {method::kRom, b.k, 0, {}}), q, 0.0, outside));
    for (const auto& sm : d.models) {
      if (sm.k != b.k) continue;
      if (methodInfo(sm.method).needsFullResidual) {  // gp-adeim: on the full system, adapting as it runs
        Teuchos::Time clock("adaptive setup");
        clock.start();
        const auto hr = rm.adaptiveModel(sm.k, sm.m, inst, A, q.dt);
        const double setup = clock.stop();
        const ModelRun run = evaluateRun(settings, fom, *inst.system, *A, *hr, {sm.method, sm.k, sm.m, adeimUpdateHook(*hr)});
        out.push_back(recordOf(run, q, setup, outside));
        out.back().queryEstimate =  // as gphr query reports it (collective, as this point's evaluation)
            rm.simulateAdaptive(sm.k, sm.m, q.mu, q.T, q.dt, ctx.comm, {}, nullptr, true).errorEstimate;
        continue;
      }
      OnlineModel online = rm.instantiate(sm.method, sm.k, sm.m, q.mu, true, q.setup);
      const ModelRun run = evaluateRun(settings, fom, *inst.system, *A, online.model(), {sm.method, sm.k, sm.m, {}});
      out.push_back(recordOf(run, q, online.setupSeconds(), outside));
      out.back().queryEstimate = online.simulate(q.T, q.dt).errorEstimate;  // as gphr query reports it
    }
  }
  return out;
}

}  // namespace

int runValidate(const std::string& modelPath, const std::string& testsPath, const std::string& outputDir,
                const RCP<const Comm>& comm) {
  requireOutputsApart({{modelPath, "the model file"}, {testsPath, "the validation file"}}, {{outputDir, "--output"}});
  ProgressWatch::configure(2.0, comm->getRank() == 0);  // gphr run's default output.progressSeconds
  const auto loaded = loadOnEveryRank(modelPath, comm);
  const ReducedModel& rm = *loaded;
  const auto& d = rm.data();
  for (const auto& b : d.bases)
    GPHR_REQUIRE(b.hasBasis, InputError, "reduced-model file '", modelPath, "' holds no basis for k = ", b.k,
                 ": gphr validate lifts the reduced states to compare them with the full model; build the file with "
                 "build.withBasis: true");
  const auto points = readQueriesOnEveryRank(testsPath, rm, QueryFileKind::Validation, comm);
  checkLiftingBases(rm, points, QueryFileKind::Validation, comm);
  RunContext ctx;
  ctx.comm = comm;
  ctx.outputDir = outputDir;
  makeDirectory(outputDir, comm);
  const OutputLock lock(outputDir, "validate", comm);  // before anything is made inside: a refused run leaves nothing
  makeDirectory(outputDir + "/fom", comm);
  makeDirectory(outputDir + "/points", comm);
  std::vector<ValidationRecord> all;
  std::vector<double> fomSeconds;
  Teuchos::Time wall("validate");
  wall.start();
  std::vector<std::vector<ValidationRecord>> stored(points.size());
  std::vector<double> storedFom(points.size(), NAN);
  std::vector<char> done(points.size());
  for (size_t i = 0; i < points.size(); ++i)
    done[i] = readPointRecords(outputDir + "/points/" + points[i].name + ".txt", resultKey(points[i], d), comm,
                               stored[i], storedFom[i]);
  if (!points.empty()) fullModelsOverGroups(ctx, rm, points, done);
  for (size_t i = 0; i < points.size(); ++i) {
    const auto& q = points[i];
    const std::string key = resultKey(q, d);
    std::vector<ValidationRecord> recs = std::move(stored[i]);
    double tFom = storedFom[i];
    bool cachedFom = false, reused = done[i];
    if (!reused) {
      const ProgressPhase phase(detail::concat("validate: point ", i + 1, "/", points.size(), " (", q.name, ")"));
      try {
        recs = evaluatePoint(ctx, rm, q, tFom, cachedFom);
      } catch (const SolverError& e) {  // collective: every rank of the run fails at the same point
        throw SolverError(detail::concat(pointName(q, d), ": ", e.what()));
      }
      writePointRecords(outputDir + "/points/" + q.name + ".txt", key, recs, tFom, comm);
    }
    all.insert(all.end(), recs.begin(), recs.end());
    fomSeconds.push_back(tFom);
    if (comm->getRank() == 0) {
      const double t = wall.totalElapsedTime(true);
      progressLine("[gphr] validate: point %zu/%zu (%s)%s, %zu models, elapsed %.1f s, ETA %.1f s", i + 1,
                   points.size(), q.name.c_str(), reused ? " reused" : cachedFom ? " (full model cached)" : "",
                   recs.size(), t, t / (i + 1) * (points.size() - i - 1));
    }
  }
  // rank 0 writes the report; its failure (a full disk, say) ends every rank
  onRootAgreed(comm, "gphr validate: the report",
               [&] { writeValidationReport(outputDir, rm, points, all, fomSeconds); });
  return 0;
}

}  // namespace gphr
