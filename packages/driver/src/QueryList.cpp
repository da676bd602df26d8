#include "gphr/core/Provenance.hpp"
#include "gphr/driver/QueryList.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "gphr/core/Error.hpp"
#include "gphr/core/Fnv1a.hpp"
#include "gphr/core/RankGroups.hpp"
#include "gphr/driver/OutputDirectory.hpp"
#include "gphr/driver/InputFile.hpp"
#include "gphr/hyper/ReducedModelFile.hpp"
#include "gphr/core/Method.hpp"

namespace gphr {

namespace {

const std::vector<std::string> kQueryKeys = {"method", "k",     "m",     "T",          "dt",
                                             "saveEvery", "probes", "setup", "extrapolate", "states"};
const std::vector<std::string> kPointKeys = {"T", "dt", "saveEvery", "setup"};

const std::vector<std::string>& keysOf(QueryFileKind kind) {
  return kind == QueryFileKind::Queries ? kQueryKeys : kPointKeys;
}

std::string allowedKeys(const ReducedModelData& d, QueryFileKind kind) {
  std::string s;
  for (const auto& p : d.parameterNames) s += p + ", ";
  for (const auto& k : keysOf(kind)) s += k + (k == keysOf(kind).back() ? "" : ", ");
  return s;
}

double numberAt(const Teuchos::ParameterList& pl, const std::string& key, const std::string& where) {
  if (pl.isType<double>(key)) return pl.get<double>(key);
  if (pl.isType<int>(key)) return pl.get<int>(key);
  throw InputError(detail::concat(where, ": key '", key, "' must be a number"));
}

long wholeAt(const Teuchos::ParameterList& pl, const std::string& key, const std::string& where, long lo) {
  GPHR_REQUIRE(pl.isType<int>(key), InputError, where, ": key '", key, "' must be a whole number");
  const long v = pl.get<int>(key);
  GPHR_REQUIRE(v >= lo, InputError, where, ": key '", key, "' has value ", v, "; allowed: >= ", lo);
  return v;
}

bool flagAt(const Teuchos::ParameterList& pl, const std::string& key, const std::string& where) {
  GPHR_REQUIRE(pl.isType<bool>(key), InputError, where, ": key '", key, "' must be true or false");
  return pl.get<bool>(key);
}

// Applies the keys of one mapping (defaults or a point) to q; parameters go to mu (NaN: unset).
void apply(const Teuchos::ParameterList& pl, const ReducedModelData& d, QueryFileKind kind, const std::string& where,
           Query& q) {
  for (auto it = pl.begin(); it != pl.end(); ++it) {
    const std::string key = pl.name(it);
    const auto p = std::find(d.parameterNames.begin(), d.parameterNames.end(), key);
    const auto& keys = keysOf(kind);
    GPHR_REQUIRE(p != d.parameterNames.end() || std::find(keys.begin(), keys.end(), key) != keys.end(), InputError,
                 where, ": unknown key '", key, "'; allowed: ", allowedKeys(d, kind));
    if (p != d.parameterNames.end()) q.mu[p - d.parameterNames.begin()] = numberAt(pl, key, where);
    else if (key == "method") {
      GPHR_REQUIRE(pl.isType<std::string>(key), InputError, where, ": key 'method' must be a method name");
      q.method = pl.get<std::string>(key);
    }
    else if (key == "k") q.k = static_cast<int>(wholeAt(pl, key, where, 1));
    else if (key == "m") q.m = static_cast<int>(wholeAt(pl, key, where, 1));
    else if (key == "T") q.T = numberAt(pl, key, where);
    else if (key == "dt") q.dt = numberAt(pl, key, where);
    else if (key == "saveEvery") q.saveEvery = wholeAt(pl, key, where, 1);
    else if (key == "probes") q.probes = flagAt(pl, key, where);
    else if (key == "extrapolate") q.extrapolate = flagAt(pl, key, where);
    else if (key == "states") q.states = flagAt(pl, key, where);
    else if (key == "setup") {
      const std::string v = pl.isType<std::string>(key) ? pl.get<std::string>(key) : "";
      GPHR_REQUIRE(v == "interpolated" || v == "exact", InputError, where, ": key 'setup' has value '", v,
                   "'; allowed: interpolated, exact");
      q.setup = v == "exact" ? SetupRoute::Exact : SetupRoute::Interpolated;
    }
  }
}

// Model defaults: the only k and m of the file when it holds one, its T and dt.
Query fileDefaults(const ReducedModelData& d) {
  Query q;
  q.mu.assign(d.parameterNames.size(), NAN);
  std::set<int> ks, ms;
  for (const auto& x : d.models) ks.insert(x.k), ms.insert(x.m);
  if (ks.size() == 1) q.k = *ks.begin();
  if (ms.size() == 1) q.m = *ms.begin();
  q.T = d.T, q.dt = d.dt;
  return q;
}

// A query's name names its result files (queries/NAME.h5, points/NAME.txt) and an HDF5 group.
void checkQueryName(const std::string& name) {
  const std::string shown = name.size() > 40 ? name.substr(0, 40) + "..." : name;
  GPHR_REQUIRE(!name.empty() && name.size() <= kMaxQueryName, InputError, "query name '", shown, "' has ",
               name.size(), " characters; allowed: 1 to ", kMaxQueryName);
  GPHR_REQUIRE(name.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789._-") ==
                       std::string::npos &&
                   name[0] != '.' && name.rfind("grid-", 0) != 0,
               InputError, "query name '", shown,
               "': allowed: letters, digits, '.', '_' and '-', not starting with '.' or 'grid-'");
}

// Everything that can fail later, checked now on every rank.
void check(const Query& q, const ReducedModel& model, QueryFileKind kind, const std::string& where) {
  const auto& d = model.data();
  for (size_t p = 0; p < q.mu.size(); ++p) {
    GPHR_REQUIRE(std::isfinite(q.mu[p]), InputError, where, ": parameter '", d.parameterNames[p],
                 "' is not given (in the query or in defaults)");
    const bool inside = q.mu[p] >= d.box[p].first && q.mu[p] <= d.box[p].second;
    GPHR_REQUIRE(inside || q.extrapolate || kind == QueryFileKind::Validation, InputError, where, ": ", d.parameterNames[p], " = ", q.mu[p],
                 " is outside the training box [", d.box[p].first, ", ", d.box[p].second,
                 "]; allowed: inside it, or extrapolate: true");
  }
  if (kind == QueryFileKind::Queries) {
    GPHR_REQUIRE(q.k > 0 && q.m > 0, InputError, where, ": k and m must be given (the file holds ", d.modelList(),
                 d.queryDefaults.empty() ? "; a file built with --target-error gives defaults per method)" : ")");
    try {
      d.model(q.method, q.k, q.m);
    } catch (const InputError& e) {
      throw InputError(detail::concat(where, ": ", e.what()));
    }
    GPHR_REQUIRE(q.setup != SetupRoute::Exact || d.basis(q.k).hasBasis, InputError, where,
                 ": setup 'exact' needs the basis in the model file (build with build.withBasis: true)");
    GPHR_REQUIRE(!q.states || d.basis(q.k).hasBasis, InputError, where,
                 ": states: true lifts whole states and needs the basis in the model file (build with "
                 "build.withBasis: true)");
  }
  try {
    // checked before anything of the run's length is allocated (H_hr is kept at every step), and
    // before the whole-number test, which cannot resolve a ratio beyond 2^53
    GPHR_REQUIRE(!(q.dt > 0 && q.T / q.dt > kMaxQuerySteps + 0.5), InputError, "T / dt = ", q.T / q.dt, " steps (T = ", q.T,
                 ", dt = ", q.dt, "); allowed: at most ", kMaxQuerySteps);
    wholeSteps(q.T, q.dt);
  } catch (const InputError& e) {
    throw InputError(detail::concat(where, ": ", e.what()));
  }
}

std::vector<double> gridValues(const Teuchos::ParameterList& grid, const std::string& key) {
  std::vector<double> spec;
  if (grid.isType<Teuchos::Array<double>>(key))
    for (double x : grid.get<Teuchos::Array<double>>(key)) spec.push_back(x);
  else if (grid.isType<Teuchos::Array<int>>(key))
    for (int x : grid.get<Teuchos::Array<int>>(key)) spec.push_back(x);
  std::ostringstream given;  // the value as given, for the message
  if (spec.empty()) given << grid.getEntry(key).getAny(false);
  for (size_t i = 0; i < spec.size(); ++i) given << (i ? ", " : "[") << spec[i] << (i + 1 == spec.size() ? "]" : "");
  GPHR_REQUIRE(spec.size() == 3 && std::isfinite(spec[0]) && std::isfinite(spec[1]) && spec[2] >= 1 &&
                   spec[2] == std::floor(spec[2]) && spec[2] <= kMaxQueries,
               InputError, "queries.grid: key '", key, "' is ", given.str(),
               "; allowed: [from, to, count], finite ends and a whole count from 1 to ", kMaxQueries);
  // one point is [x, x, 1]: [from, to, 1] with from != to would silently drop `to`
  GPHR_REQUIRE(spec[2] != 1 || spec[0] == spec[1], InputError, "queries.grid: key '", key, "' is [", spec[0], ", ",
               spec[1], ", 1], one point of two ends; allowed: a count >= 2, or [x, x, 1] for the one point x");
  const long n = static_cast<long>(spec[2]);
  std::vector<double> v;
  for (long i = 0; i < n; ++i) v.push_back(n == 1 ? spec[0] : spec[0] + (spec[1] - spec[0]) * i / (n - 1));
  return v;
}

void addGrid(const Teuchos::ParameterList& grid, const ReducedModelData& d, const Query& base, std::vector<Query>& out) {
  std::vector<std::vector<double>> axes(d.parameterNames.size());
  for (auto it = grid.begin(); it != grid.end(); ++it) {
    const auto p = std::find(d.parameterNames.begin(), d.parameterNames.end(), grid.name(it));
    GPHR_REQUIRE(p != d.parameterNames.end(), InputError, "queries.grid: unknown parameter '", grid.name(it),
                 "'; allowed: the scene's parameters");
    axes[p - d.parameterNames.begin()] = gridValues(grid, grid.name(it));
  }
  size_t total = 1;
  for (size_t p = 0; p < axes.size(); ++p) {
    if (axes[p].empty()) axes[p] = {base.mu[p]};  // not gridded: the default (checked later)
    total *= axes[p].size();
    GPHR_REQUIRE(total <= kMaxQueries, InputError, "queries.grid has ", total, " or more points; allowed: at most ",
                 kMaxQueries, " queries in one file");
  }
  for (size_t j = 0; j < total; ++j) {
    Query q = base;
    for (size_t p = axes.size(), r = j; p-- > 0; r /= axes[p].size()) q.mu[p] = axes[p][r % axes[p].size()];
    char name[32];
    std::snprintf(name, sizeof name, "grid-%04zu", j);
    q.name = name;
    out.push_back(q);
  }
}

}  // namespace

std::string Query::key() const {
  std::string s = detail::concat("name=", name, ";method=", method, ";k=", k, ";m=", m, ";saveEvery=", saveEvery,
                                 ";probes=", probes, ";setup=", setup == SetupRoute::Exact ? "exact" : "interpolated",
                                 ";extrapolate=", extrapolate, ";states=", states);
  char buf[64];
  for (double x : mu) std::snprintf(buf, sizeof buf, ";mu=%.17g", x), s += buf;
  std::snprintf(buf, sizeof buf, ";T=%.17g;dt=%.17g", T, dt);
  return s + buf;
}

std::string resultKey(const Query& q, const ReducedModelData& data) {
  return q.key() + ";model=" + data.checksum + ";gphr=" + gphrVersion();
}

void checkLiftingBases(const ReducedModel& model, const std::vector<Query>& queries, QueryFileKind kind,
                       const RCP<const Comm>& comm) {
  std::set<int> ks;
  const std::vector<double>* mu = nullptr;
  for (const auto& q : queries) {
    const bool lifts = kind == QueryFileKind::Validation || q.setup == SetupRoute::Exact || q.states ||
                       methodInfo(q.method).needsFullResidual;
    if (!lifts) continue;
    if (kind == QueryFileKind::Validation)
      for (const auto& b : model.data().bases) ks.insert(b.k);
    else
      ks.insert(q.k);
    if (!mu) mu = &q.mu;
  }
  if (ks.empty()) return;
  const auto inst = model.scene().instantiate(comm, *mu, true);
  for (int k : ks) model.basis(k, inst.system->space());
}

namespace {

// Collective: `work` on every rank; a failure on some ranks only says so (the ranks do not see the
// same input), then every rank throws the lowest failing rank's error (agreeOnFailure).
template <class Work>
void onEveryRank(const RCP<const Comm>& comm, Work&& work) {
  GroupFailure failure = failureOf("", "", work);
  const int mine = failure.text.empty() ? 0 : 1;
  int failing = 0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, mine, Teuchos::outArg(failing));
  if (mine && failing < comm->getSize())
    failure.text += detail::concat(" (on rank ", comm->getRank(), "; ", comm->getSize() - failing, " of the ",
                                   comm->getSize(), " ranks read it: the ranks do not see the same input)");
  agreeOnFailure(*comm, failure);
}

// Collective: InputError on every rank unless `text` is the same on all (compared by its hash).
void requireSameOnRanks(const RCP<const Comm>& comm, const std::string& text, const std::string& what) {
  Fnv1a h;
  h.text(text);
  const std::string hex = h.hex();
  const long long mine = static_cast<long long>(std::stoull(hex.substr(hex.size() - 15), nullptr, 16));
  long long lo = 0, hi = 0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MIN, mine, Teuchos::outArg(lo));
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, mine, Teuchos::outArg(hi));
  GPHR_REQUIRE(lo == hi, InputError, "the ranks read different contents of ", what, "; allowed: one input that every "
               "rank reads alike (a file system all nodes share, not changed while gphr starts)");
}

}  // namespace

std::unique_ptr<ReducedModel> loadOnEveryRank(const std::string& path, const RCP<const Comm>& comm) {
  std::unique_ptr<ReducedModel> model;
  const std::string what = "reduced-model file '" + path + "'";
  onEveryRank(comm, [&] { model = std::make_unique<ReducedModel>(path); });
  requireSameOnRanks(comm, model->data().checksum, what);
  return model;
}

std::vector<Query> readQueriesOnEveryRank(const std::string& path, const ReducedModel& model, QueryFileKind kind,
                                          const RCP<const Comm>& comm) {
  std::vector<Query> out;
  const std::string what = (kind == QueryFileKind::Queries ? "queries file '" : "validation file '") + path + "'";
  onEveryRank(comm, [&] { out = readQueries(path, model, kind); });
  std::string keys;
  for (const auto& q : out) keys += q.key() + "\n";
  requireSameOnRanks(comm, keys, what);
  return out;
}

std::vector<Query> readQueries(const std::string& path, const ReducedModel& model, QueryFileKind kind) {
  const std::string root = kind == QueryFileKind::Queries ? "queries" : "validate";
  const auto pl = readParameterFile(path, root);
  const auto& d = model.data();
  std::vector<Query> out;
  try {
    GPHR_REQUIRE(pl->name() == root, InputError, "the top level must be the single key '", root, "' (found '",
                 pl->name(), "')");
    for (auto it = pl->begin(); it != pl->end(); ++it) {
      const std::string& section = pl->name(it);
      GPHR_REQUIRE(section == "defaults" || section == "points" || section == "grid", InputError,
                   "unknown section '", root, ".", section, "'; allowed: defaults, points, grid");
      std::ostringstream given;
      if (!pl->isSublist(section)) given << pl->entry(it).getAny(false);
      GPHR_REQUIRE(pl->isSublist(section), InputError, root, ".", section, " is ", given.str(),
                   "; allowed: a mapping (",
                   section == "grid" ? "parameter: [from, to, count]" : section == "points" ? "name: {keys}" : "key: value",
                   ", ...)");
    }
    Query base = fileDefaults(d);
    if (pl->isSublist("defaults")) apply(pl->sublist("defaults"), d, kind, root + ".defaults", base);
    if (pl->isSublist("points")) {
      const auto& points = pl->sublist("points");
      for (auto it = points.begin(); it != points.end(); ++it) {
        const std::string name = points.name(it), where = "query '" + name + "'";
        GPHR_REQUIRE(points.isSublist(name), InputError, where, ": must be a mapping of parameters and keys");
        checkQueryName(name);
        Query q = base;
        q.name = name;
        apply(points.sublist(name), d, kind, where, q);
        out.push_back(q);
      }
    }
    if (pl->isSublist("grid")) addGrid(pl->sublist("grid"), d, base, out);
    GPHR_REQUIRE(!out.empty(), InputError, "no query: give queries.points or queries.grid");
    GPHR_REQUIRE(out.size() <= kMaxQueries, InputError, out.size(), " queries; allowed: at most ", kMaxQueries);
    for (auto& q : out) {
      // k and m the query leaves open: the file's default for its method (a greedy build's
      // cheapest model that met the target; ReducedModelData::queryDefaults)
      const QueryDefault* fallback = kind == QueryFileKind::Queries ? d.queryDefault(q.method) : nullptr;
      if (fallback && q.k == 0) q.k = fallback->k;
      if (fallback && q.m == 0) q.m = fallback->m;
      check(q, model, kind, "query '" + q.name + "'");
    }
  } catch (const InputError& e) {
    throw InputError(detail::concat(root, " file '", path, "': ", e.what()));
  }
  return out;
}

}  // namespace gphr
