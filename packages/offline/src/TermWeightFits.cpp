#include "gphr/offline/TermWeightFits.hpp"

#include <Teuchos_Time.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gphr/core/Error.hpp"
#include "gphr/core/Method.hpp"

namespace gphr {

namespace {
// gp-eqp-refit: GP-DEIM's terms, weights refit (one fit per budget, off the NNLS path)
bool isRefit(const std::string& method) { return methodInfo(method).fit == TermWeightFit::LeastSquaresRefit; }
}  // namespace

TermWeightFits::TermWeightFits(const Scene& scene, RCP<const Comm> comm, const TrainingResult& training,
                               const MultiVector& A, const QuadratureOptions& options, double tolerance,
                               std::vector<int> budgets, DeimTerms deimTerms, const ArtifactsCache* cache,
                               std::string nnlsKey, std::string refitKey)
    : scene_(scene), comm_(std::move(comm)), snapshots_(training), A_(A),
      k_(static_cast<int>(A.getNumVectors()) / 2), opt_(options), tolerance_(tolerance), budgets_(std::move(budgets)),
      deimTerms_(std::move(deimTerms)), nnlsKey_(std::move(nnlsKey)), refitKey_(std::move(refitKey)) {
  if (cache) cache_.emplace(*cache);
}

CachedFit TermWeightFits::get(const std::string& method, int m) {
  const bool refit = isRefit(method);
  CachedFit out;
  if (read(method, m, out)) return out;
  if (refit) {  // its own fit, never in computed_ (the NNLS path's fits by budget)
    out.fit = refitQuadrature(training(), deimTerms_(m));
    return finish(method, m, out);
  }
  if (!computed_.count(m)) {
    // One greedy path for every budget not in the cache (each budget's fit is the path up to
    // it, and its time the path's time to it).
    std::vector<int> budgets{m};  // m was read above: not in the cache (or damaged there)
    for (int b : budgets_)
      if (CachedFit c; b != m && !read(method, b, c)) budgets.push_back(b);
    const auto path = nnlsQuadraturePath(training(), budgets, tolerance_);
    for (size_t i = 0; i < budgets.size(); ++i) computed_[budgets[i]] = path[i];
  }
  out.fit = computed_.at(m);
  finish(method, m, out);
  computed_.erase(m);
  return out;
}

// A fit computed now: its residual at the exact rows (when the training rows were sketched), its
// times, stored in the cache.
CachedFit& TermWeightFits::finish(const std::string& method, int m, CachedFit& out) {
  out.exactResidual = opt_.sketchRows > 0 ? exactRowsResidual(systems(), snapshots_.snapshots, A_, opt_, out.fit)
                                          : out.fit.residual;
  out.fitSeconds = out.fit.seconds;
  out.trainingSeconds = trainingSeconds_;
  store(method, m, out);
  return out;
}

std::map<int, QuadratureFit> TermWeightFits::all(const std::string& method, const std::vector<int>& ms,
                                                 std::map<int, std::string>& skipped) {
  std::map<int, QuadratureFit> out;
  for (int m : ms) {
    try {
      out[m] = get(method, m).fit;
    } catch (const InputError& e) {
      skipped[m] = e.what();
    }
  }
  return out;
}

std::string TermWeightFits::name(const std::string& method, int m) const {
  return "/eqp/" + method + "_k" + std::to_string(k_) + "_m" + std::to_string(m);
}

// The revision: 2, the budgets' fits along one greedy path (the same fits, times along the path).
std::string TermWeightFits::key(const std::string& method, int m) const {
  return (isRefit(method) ? refitKey_ : nnlsKey_) + "eqp revision 2, k = " + std::to_string(k_) +
         ", m = " + std::to_string(m);
}

namespace {
constexpr size_t kDiagnostics = 5;  // fit residual, exact-rows residual, selections, fit seconds, training seconds

// What is wrong with a stored fit (terms over rows of G, `rows` of them, and their weights; its
// diagnostics), "" if nothing: a file changed after it was written would otherwise put rows
// outside G or NaN weights into the model file unseen. No fingerprint: every value is checked.
std::string fitProblem(const std::vector<double>& a, const std::vector<double>& diagnostics, GO rows, bool nnls) {
  // (no terms is a fit: NNLS stops at once where no term correlates with the target)
  if (a.size() % 2 != 0) return detail::concat("holds ", a.size(), " numbers (allowed: 2 x terms)");
  if (diagnostics.size() != kDiagnostics)
    return detail::concat("holds ", diagnostics.size(), " diagnostics (allowed: ", kDiagnostics, ")");
  const size_t p = a.size() / 2;
  std::vector<GO> seen;
  for (size_t j = 0; j < p; ++j) {
    if (!(a[j] >= 0 && a[j] < static_cast<double>(rows)) || a[j] != std::floor(a[j]))
      return detail::concat("term ", j + 1, " is ", a[j], " (allowed: a row of G, 0 to ", rows - 1, ")");
    seen.push_back(static_cast<GO>(a[j]));
    if (!std::isfinite(a[p + j]) || (nnls && a[p + j] < 0.0))
      return detail::concat("weight ", j + 1, " is ", a[p + j], " (allowed: ", nnls ? "finite, >= 0" : "finite", ")");
  }
  std::sort(seen.begin(), seen.end());
  if (std::adjacent_find(seen.begin(), seen.end()) != seen.end()) return "names a row of G twice";
  return "";
}
}  // namespace

// Separate opens: the DEIM basis of the refit opens the same file in between.
bool TermWeightFits::read(const std::string& method, int m, CachedFit& out) {
  if (!cache_) return false;
  const std::string n = name(method, m);
  std::vector<double> a, d;
  {
    const auto f = cache_->open();
    if (!ArtifactsCache::holds(*f, n, key(method, m))) return false;
    a = f->readArray(n);  // row 0 the terms, row 1 the weights
    d = f->doubleAttribute(n, "diagnostics");
    out.fit.stop = f->stringAttribute(n, "stop");
  }
  const GO rows = static_cast<GO>(systems()[0]->nonlinearTerm().rowMap()->getGlobalNumElements());
  const std::string problem = fitProblem(a, d, rows, !isRefit(method));
  if (!problem.empty()) {  // computed afresh, as a basis whose fingerprint no longer matches
    if (comm_->getRank() == 0)
      std::fprintf(stderr, "[gphr] eqp: %s in '%s' %s: computed afresh\n", n.c_str(), cache_->path().c_str(),
                   problem.c_str());
    out = CachedFit();
    return false;
  }
  const size_t p = a.size() / 2;
  for (size_t j = 0; j < p; ++j) out.fit.terms.push_back(static_cast<GO>(a[j])), out.fit.weights.push_back(a[p + j]);
  out.fit.residual = d[0], out.exactResidual = d[1], out.fit.iterations = static_cast<int>(d[2]);
  out.fitSeconds = d[3], out.trainingSeconds = d[4];
  out.cached = true;
  return true;
}

void TermWeightFits::store(const std::string& method, int m, const CachedFit& c) const {
  if (!cache_) return;
  const auto f = cache_->open();
  const std::string n = name(method, m);
  const size_t p = c.fit.terms.size();
  std::vector<double> a(2 * p);
  for (size_t j = 0; j < p; ++j) a[j] = static_cast<double>(c.fit.terms[j]), a[p + j] = c.fit.weights[j];
  ArtifactsCache::clear(*f, n);
  f->writeArray(n, a, 2, p);
  f->setAttribute(n, "diagnostics",
                  std::vector<double>{c.fit.residual, c.exactResidual, double(c.fit.iterations), c.fitSeconds,
                                      c.trainingSeconds});
  f->setAttribute(n, "stop", c.fit.stop);
  f->setAttribute(n, "layout", std::string("row 0: the terms (rows of G), row 1: their weights; diagnostics: "
                                           "fit residual, exact-rows residual, selections, fit seconds, training seconds"));
  cache_->seal(*f, n, key(method, m));
}

const SystemSet& TermWeightFits::systems() {
  if (systems_.empty()) systems_ = trainingSystems(scene_, comm_, snapshots_);
  return systems_;
}

const QuadratureTraining& TermWeightFits::training() {
  if (training_.termMap.is_null()) {
    Teuchos::Time clock("eqp training");
    clock.start();
    try {
      training_ = buildQuadratureTraining(systems(), snapshots_.snapshots, A_, opt_);
    } catch (const InputError& e) {  // e.g. too many rows: name the section
      throw InputError(detail::concat("eqp: ", e.what()));
    }
    trainingSeconds_ = clock.stop();
    if (comm_->getRank() == 0)
      std::fprintf(stderr, "[gphr] eqp training k = %d: %d rows%s from %ld states, %.1f s\n", k_, training_.numRows,
                   training_.sketched ? " (sketched)" : "", training_.snapshots, trainingSeconds_);
  }
  return training_;
}

}  // namespace gphr
