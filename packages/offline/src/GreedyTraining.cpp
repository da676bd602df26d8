// Greedy training to a target error (GreedyTraining.hpp).
#include "gphr/offline/GreedyTraining.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <random>

#include <Teuchos_CommHelpers.hpp>

#include "gphr/core/Error.hpp"
#include "gphr/core/Method.hpp"
#include "gphr/core/Progress.hpp"
#include "gphr/offline/ErrorCalibration.hpp"
#include "gphr/online/ReducedModel.hpp"
#include "gphr/reduction/SymplecticBasis.hpp"

namespace gphr {

std::vector<std::vector<double>> cornersAndCentre(const ParameterBox& box) {
  const size_t p = box.bounds.size();
  std::vector<std::vector<double>> out;
  for (size_t c = 0; p > 0 && c < (size_t(1) << p); ++c) {
    std::vector<double> mu;
    for (size_t i = 0; i < p; ++i) mu.push_back((c >> i) & 1 ? box.bounds[i].second : box.bounds[i].first);
    out.push_back(mu);
  }
  std::vector<double> centre;
  for (const auto& [lo, hi] : box.bounds) centre.push_back(0.5 * (lo + hi));
  out.push_back(centre);
  return out;
}

std::vector<std::vector<double>> greedyStart(const ParameterBox& box, const std::string& start) {
  GPHR_REQUIRE(start == "corners" || start == "centre", InputError, "greedy start '", start,
               "'; allowed: corners (the box's corners and centre), centre (the centre alone)");
  auto points = cornersAndCentre(box);
  if (start == "centre") points.erase(points.begin(), points.end() - 1);  // the centre is the last
  return points;
}

std::vector<std::vector<double>> candidatePoints(const ParameterBox& box, int count, unsigned long seed) {
  std::mt19937_64 gen(seed);  // its sequence is fixed by the standard; the mapping below too
  std::vector<std::vector<double>> out(static_cast<size_t>(std::max(count, 0)));
  for (auto& mu : out)
    for (const auto& [lo, hi] : box.bounds) mu.push_back(lo + (hi - lo) * (double(gen() >> 11) * 0x1.0p-53));
  return out;
}

namespace {

// Each calibrated sample-mesh model's estimate at every candidate, the candidates spread over the
// ranks (candidate c on rank c mod P; a query runs on one process and pins OpenBLAS to one thread,
// so its estimate does not depend on the rank that ran it) and summed into place (a sum with zeros
// is exact): the same numbers on every rank as one rank's. A run without an estimate counts as
// infinite (it failed). Per model key, in the file's order. Collective.
std::vector<std::pair<std::string, std::vector<double>>> estimatesAtCandidates(
    const ReducedModel& rm, const RCP<const Comm>& comm, const std::vector<std::vector<double>>& candidates, double T,
    double dt) {
  const int P = comm->getSize(), rank = comm->getRank();
  std::vector<std::pair<std::string, std::vector<double>>> out;
  for (const auto& x : rm.data().models) {
    if (x.onlineNeedsFullSystem() || !x.calibration.calibrated()) continue;  // gp-adeim: a full system per point
    std::vector<double> mine(candidates.size(), 0.0), all(candidates.size(), 0.0);
    for (size_t c = static_cast<size_t>(rank); c < candidates.size(); c += static_cast<size_t>(P)) {
      const double e = rm.instantiate(x.method, x.k, x.m, candidates[c]).simulate(T, dt).errorEstimate;
      mine[c] = std::isfinite(e) ? e : std::numeric_limits<double>::infinity();
    }
    if (!candidates.empty())
      Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, static_cast<int>(mine.size()), mine.data(), all.data());
    out.emplace_back(x.key(), std::move(all));
  }
  return out;
}

// The round's measure: the largest estimate of each model over the candidates (`largestOf`, per
// key), the best model (the smallest largest) and its estimates (`best`).
GreedyRound measureRound(const std::vector<std::pair<std::string, std::vector<double>>>& estimates,
                         std::map<std::string, double>& largestOf, std::vector<double>& best) {
  largestOf.clear();
  GreedyRound round;
  round.maxEstimate = std::numeric_limits<double>::infinity();
  for (const auto& [key, e] : estimates) {
    const double largest = e.empty() ? -1.0 : *std::max_element(e.begin(), e.end());
    largestOf[key] = largest;
    if (largest < round.maxEstimate || round.model.empty()) round.maxEstimate = largest, round.model = key, best = e;
  }
  return round;
}

}  // namespace

std::vector<size_t> pointsToAdd(const ParameterBox& box, const std::vector<std::vector<double>>& candidates,
                                const std::vector<double>& estimates, double target, int count) {
  GPHR_REQUIRE(estimates.size() == candidates.size(), InputError, estimates.size(), " estimates for ",
               candidates.size(), " candidates");
  std::vector<size_t> order(candidates.size());
  for (size_t c = 0; c < order.size(); ++c) order[c] = c;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return estimates[a] > estimates[b]; });
  const size_t p = box.bounds.size();
  // Within a round, points at least a cell of a count-point grid apart (0.5 / ceil(count^(1/p)) in
  // the box scaled to the unit cube): the round's points spread over the box's bad regions, not
  // piled onto the one a single new point would already mend.
  const double radius = p == 0 ? 0.0 : 0.5 / std::ceil(std::pow(static_cast<double>(count), 1.0 / p) - 1e-12);
  const auto distance = [&](size_t a, size_t b) {
    double d2 = 0.0;
    for (size_t i = 0; i < p; ++i) {
      const double w = box.bounds[i].second - box.bounds[i].first, d = w > 0 ? (candidates[a][i] - candidates[b][i]) / w : 0.0;
      d2 += d * d;
    }
    return std::sqrt(d2);
  };
  std::vector<size_t> out;
  for (size_t c : order) {
    if (static_cast<int>(out.size()) >= count || !(estimates[c] > target)) break;
    if (std::all_of(out.begin(), out.end(), [&](size_t a) { return distance(a, c) >= radius; })) out.push_back(c);
  }
  if (out.empty() && !order.empty()) out.push_back(order.front());  // the worst, whatever its estimate
  return out;
}

namespace {

// E_L2 of each query default at the fresh `points` (full solves, not added to the training here: no
// cache), the largest into verifiedMax. Collective.
void confirmQueryDefaults(const Scene& scene, const RCP<const Comm>& comm, const ModelBuildOptions& o,
                          const ModelBuildResult& build, const std::vector<std::vector<double>>& points,
                          std::vector<QueryDefault>& defaults) {
  if (points.empty() || defaults.empty()) return;
  const ProgressPhase phase(detail::concat("greedy: full solves at ", points.size(), " fresh points"));
  TrainingOptions fresh = o.training;
  fresh.parameters = points;
  fresh.progress = false;
  const TrainingResult reference = runTraining(scene, comm, fresh);
  const auto inst = scene.instantiate(comm, o.parameter.empty() ? cornersAndCentre(scene.parameterBox()).back()
                                                               : o.parameter, true);
  std::map<int, RCP<const MultiVector>> bases;
  for (const auto& b : build.data.bases) bases[b.k] = leadingBasis(build.basis.basis, b.k);
  const auto measured = measureModelErrors(build.data, scene, *inst.system, bases, reference, o.training.snapshotEvery,
                                           o.training.dt, o.training.steps);
  for (auto& q : defaults) {
    q.verifiedMax = 0.0;
    const auto it = measured.find(build.data.model(q.method, q.k, q.m).key());
    if (it == measured.end() || it->second.empty()) q.verifiedMax = std::numeric_limits<double>::quiet_NaN();
    else
      for (const auto& p : it->second)  // a run that failed (NaN) counts as an infinite error
        q.verifiedMax = std::max(q.verifiedMax, std::isfinite(p.error) ? p.error : std::numeric_limits<double>::infinity());
  }
}

// The greedy rounds from `params` (see buildToTargetError): build, estimate at the candidates,
// add the worst, until the best model's largest estimate meets the target, maxPoints are trained or
// no candidate is left. `out` gets the rounds, the last build and whether the target was met.
void trainRounds(const Scene& scene, const RCP<const Comm>& comm, ModelBuildOptions& o, const std::string& path,
                 const GreedyOptions& g, const ArtifactsCache* cache, const OfflineSequence::StageHook& hook,
                 std::vector<std::vector<double>>& params, std::vector<std::vector<double>>& candidates,
                 GreedyResult& out, std::map<std::string, double>& largest) {
  const std::shared_ptr<const Scene> sceneRef(&scene, [](const Scene*) {});  // not owned: the caller's
  const double dt = o.training.dt, T = dt * static_cast<double>(o.training.steps);
  for (;;) {
    o.training.parameters = params;
    o.greedyRounds = out.rounds;  // the file records the rounds so far
    out.build = buildReducedModelFile(scene, comm, o, path, cache, hook);
    std::vector<double> best;  // the best model's estimate at each candidate
    GreedyRound round = measureRound(estimatesAtCandidates(ReducedModel(path, sceneRef), comm, candidates, T, dt),
                                     largest, best);
    GPHR_REQUIRE(!round.model.empty(), InputError, "greedy training: no stored model of ", out.build.data.modelList(),
                 " has an error estimate (no training point gave both its error and its indicator)");
    round.fullSolves = static_cast<long>(params.size());
    out.met = round.maxEstimate <= g.targetError;
    const bool stop = out.met || static_cast<int>(params.size()) >= g.maxPoints || candidates.empty();
    std::vector<size_t> added;
    if (!stop) {
      added = pointsToAdd(scene.parameterBox(), candidates, best, g.targetError,
                          std::min(g.pointsPerRound, g.maxPoints - static_cast<int>(params.size())));
      round.added = candidates[added.front()];  // the worst; the round's others follow it in the training set
    }
    if (comm->getRank() == 0)
      std::fprintf(stderr, "[gphr] greedy: %zu training points, best model %s, largest estimate %.3e over %zu "
                   "candidates (target %.3e)%s\n", params.size(), round.model.c_str(), round.maxEstimate,
                   candidates.size(), g.targetError, out.met ? ": met" : stop ? ": stopped, not met" : "");
    out.rounds.push_back(round);
    if (stop) return;
    for (size_t c : added) params.push_back(candidates[c]);
    std::sort(added.begin(), added.end());
    for (auto c = added.rbegin(); c != added.rend(); ++c) candidates.erase(candidates.begin() + static_cast<long>(*c));
  }
}

// The fresh points of confirmation number `n` (0, 1, ...): the n-th g.confirmPoints of one
// seeded stream (freshPoints), so that no confirmation reuses an earlier one's points.
std::vector<std::vector<double>> confirmationPoints(const ParameterBox& box, const GreedyOptions& g, int n) {
  if (g.confirmPoints <= 0) return {};
  auto all = freshPoints(box, g.confirmPoints * (n + 1), g.seed);
  all.erase(all.begin(), all.end() - g.confirmPoints);
  return all;
}

void reportQueryDefaults(const Comm& comm, const std::vector<QueryDefault>& defaults, const GreedyOptions& g) {
  for (const auto& q : defaults) {
    char confirmed[96] = "not confirmed (build.confirmPoints: 0)";
    if (g.confirmPoints > 0)
      std::snprintf(confirmed, sizeof confirmed, "E_L2 max %.3e at %d fresh points (full solves)", q.verifiedMax,
                    g.confirmPoints);
    if (comm.getRank() == 0)
      std::fprintf(stderr, "[gphr] greedy: query default %s k=%d m=%d: estimated max %.3e over the candidates%s, %s\n",
                   q.method.c_str(), q.k, q.m, q.estimatedMax, q.met ? "" : " (target not met: the method's best)",
                   confirmed);
  }
}

}  // namespace

double onlineCostProxy(int k, int m) {
  const double r = 2.0 * k;
  return r * r * r / 3.0 + 2.0 * m * r * r;
}

std::vector<QueryDefault> chooseQueryDefaults(const std::vector<StoredHyperModel>& models,
                                              const std::map<std::string, double>& largest, double target) {
  std::map<std::string, QueryDefault> best;  // per method
  for (const auto& x : models) {
    const auto it = largest.find(x.key());
    if (it == largest.end()) continue;  // not estimated (gp-adeim)
    QueryDefault q{x.method, x.k, x.m, it->second, std::numeric_limits<double>::quiet_NaN(), it->second <= target};
    const auto b = best.find(x.method);
    const auto better = [](const QueryDefault& a, const QueryDefault& c) {  // a before c?
      if (a.met != c.met) return a.met;
      const double ca = onlineCostProxy(a.k, a.m), cc = onlineCostProxy(c.k, c.m);
      // not met: the smaller estimate first; met: the cheaper first; then the smaller k, m
      if (!a.met && a.estimatedMax != c.estimatedMax) return a.estimatedMax < c.estimatedMax;
      return ca < cc || (ca == cc && std::make_pair(a.k, a.m) < std::make_pair(c.k, c.m));
    };
    if (b == best.end() || better(q, b->second)) best[x.method] = q;
  }
  std::vector<QueryDefault> out;
  for (const auto& [method, q] : best) out.push_back(q);
  return out;
}

std::vector<std::vector<double>> freshPoints(const ParameterBox& box, int count, unsigned long seed) {
  return candidatePoints(box, count, seed ^ 0x9e3779b97f4a7c15UL);  // a stream of its own, not the candidates'
}

GreedyResult buildToTargetError(const Scene& scene, const RCP<const Comm>& comm, ModelBuildOptions o,
                                const std::string& path, const GreedyOptions& g, const ArtifactsCache* cache,
                                const OfflineSequence::StageHook& hook) {
  GPHR_REQUIRE(std::isfinite(g.targetError) && g.targetError > 0.0 && g.targetError < 1.0, InputError,
               "target error ", g.targetError, "; allowed: 0 < target < 1 (a relative error E_L2)");
  GPHR_REQUIRE(g.candidates >= 1 && g.candidates <= 100000, InputError, "greedy candidates ", g.candidates,
               "; allowed: 1 to 100000");
  GPHR_REQUIRE(g.pointsPerRound >= 1 && g.pointsPerRound <= 1000, InputError, "greedy points per round ",
               g.pointsPerRound, "; allowed: 1 to 1000");
  GPHR_REQUIRE(o.file.indicatorDofs > 0, InputError,
               "greedy training needs the error indicator: build.indicatorDofs = 0; allowed: >= 1");
  GPHR_REQUIRE(std::any_of(o.methods.begin(), o.methods.end(),
                           [](const std::string& m) { return !methodInfo(m).needsFullResidual; }),
               InputError, "greedy training estimates the sample-mesh models at its candidates; the methods asked "
               "for have none (gp-adeim needs a full system per point); allowed: gp-deim, gp-eqp or gp-eqp-refit "
               "among them");
  const ParameterBox& box = scene.parameterBox();
  std::vector<std::vector<double>> params = greedyStart(box, g.start),
                                   candidates = candidatePoints(box, g.candidates, g.seed);
  GPHR_REQUIRE(g.maxPoints >= static_cast<int>(params.size()), InputError, "greedy training starts from ",
               params.size(), " points (build.greedyStart '", g.start, "'); allowed: build.maxTrainingPoints >= that, got ",
               g.maxPoints);
  o.file.targetError = g.targetError;
  const auto start = std::chrono::steady_clock::now();
  GreedyResult out;
  std::map<std::string, double> largest;  // the last round's, per model
  for (int confirmation = 0;; ++confirmation) {
    trainRounds(scene, comm, o, path, g, cache, hook, params, candidates, out, largest);
    // Per method the cheapest model that met the target (else its best), confirmed by full solves
    // at fresh points: the defaults of a query that names a method only.
    o.queryDefaults = chooseQueryDefaults(out.build.data.models, largest, g.targetError);
    const auto fresh = confirmationPoints(box, g, confirmation);
    confirmQueryDefaults(scene, comm, o, out.build, fresh, o.queryDefaults);
    reportQueryDefaults(*comm, o.queryDefaults, g);
    // The estimate is calibrated on the training points: where the full solves at the fresh points
    // say a default that met the target by its estimate does not, those points join the training
    // (solved again there: the confirmation keeps no states) and the rounds go on, with fresh
    // points of their own next time.
    const bool missed = !fresh.empty() && out.met && std::any_of(o.queryDefaults.begin(), o.queryDefaults.end(), [&](const QueryDefault& q) {
      return q.met && !(q.verifiedMax <= g.targetError);
    });
    if (!missed) break;
    const bool room = static_cast<int>(params.size() + fresh.size()) <= g.maxPoints;
    if (comm->getRank() == 0)
      std::fprintf(stderr, "[gphr] greedy: the full solves at the fresh points exceed the target %.3e%s\n",
                   g.targetError, room ? ": they join the training and the rounds go on"
                                       : ": stopped (build.maxTrainingPoints), the target is not confirmed");
    if (!room) break;
    out.rounds.back().added = fresh.front();  // the round's record: the first of the points it adds
    params.insert(params.end(), fresh.begin(), fresh.end());
    out.met = false;
  }
  // The file once more with every round in it: its stages are all in the cache (or in memory: the
  // training again without one), only the calibration and the write are redone.
  o.greedyRounds = out.rounds;
  o.earlierSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.build = buildReducedModelFile(scene, comm, o, path, cache, hook);
  return out;
}

}  // namespace gphr
