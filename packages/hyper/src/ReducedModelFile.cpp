#include "gphr/hyper/ReducedModelFile.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_DefaultSerialComm.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "gphr/core/Error.hpp"
#include "gphr/core/Method.hpp"
#include "gphr/core/Fnv1a.hpp"
#include "gphr/core/ColumnFingerprint.hpp"
#include "gphr/io/Hdf5File.hpp"

namespace gphr {

namespace {

const char* kFormat = "gphr reduced model";

std::vector<double> toDoubles(const std::vector<GO>& v) { return std::vector<double>(v.begin(), v.end()); }
std::vector<double> toDoubles(const std::vector<size_t>& v) { return std::vector<double>(v.begin(), v.end()); }
std::string basisGroup(int k) { return "/k" + std::to_string(k); }

// Every value finite; InputError naming the dataset, the entry and the value otherwise.
const std::vector<double>& finite(const std::vector<double>& v, const std::string& what) {
  for (size_t i = 0; i < v.size(); ++i)
    GPHR_REQUIRE(std::isfinite(v[i]), InputError, what, " has entry ", i, " = ", v[i], "; allowed: finite numbers");
  return v;
}

// Whole numbers in [lo, hi], converted: indices and counts are checked before any is used.
template <class T>
std::vector<T> wholeNumbers(const std::vector<double>& v, const std::string& what, double lo, double hi) {
  std::vector<T> out;
  out.reserve(v.size());
  for (size_t i = 0; i < v.size(); ++i) {
    GPHR_REQUIRE(std::isfinite(v[i]) && v[i] == std::floor(v[i]) && v[i] >= lo && v[i] <= hi, InputError, what,
                 " has entry ", i, " = ", v[i], "; allowed: whole numbers from ", lo, " to ", hi);
    out.push_back(static_cast<T>(v[i]));
  }
  return out;
}

// One whole number of an attribute.
long wholeAttribute(const Hdf5File& f, const std::string& object, const std::string& key, double lo, double hi) {
  const auto v = f.doubleAttribute(object, key);
  GPHR_REQUIRE(v.size() == 1, InputError, "attribute '", key, "' of '", object, "' has ", v.size(),
               " values; allowed: one");
  return wholeNumbers<long>(v, "attribute '" + key + "' of '" + object + "'", lo, hi).front();
}

// Largest state and term index a file may name (GO range), and the largest sizes it may declare.
constexpr double kMaxIndex = 9.0e15, kMaxReducedSize = 100000, kMaxNodes = 4096;

// Ascending and unique (DEIM rows, reference and stencil entries are sets).
template <class T>
void requireAscending(const std::vector<T>& v, const std::string& what) {
  for (size_t i = 1; i < v.size(); ++i)
    GPHR_REQUIRE(v[i - 1] < v[i], InputError, what, " is not ascending and unique at entry ", i, " (", v[i - 1],
                 ", ", v[i], ")");
}

// A query default as the file names it: "METHOD k=K m=M" (readQueryDefaults parses it back).
std::string queryDefaultText(const QueryDefault& q) { return detail::concat(q.method, " k=", q.k, " m=", q.m); }

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ",") + x;
  return s;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string x; std::getline(in, x, sep);) out.push_back(x);
  return out;
}

// Rows x cols of a vector that may be empty (HDF5 datasets of zero rows are avoided: a
// placeholder row of one zero, with the true row count in an attribute).
void writeMatrix(Hdf5File& f, const std::string& name, const std::vector<double>& data, size_t rows, size_t cols) {
  if (rows == 0) f.writeArray(name, {0.0}, 1, 1);
  else f.writeArray(name, data, rows, cols);
  f.setAttribute(name, "rows", std::vector<double>{double(rows)});
}
std::vector<double> readMatrix(const Hdf5File& f, const std::string& name) {
  const size_t rows = static_cast<size_t>(f.doubleAttribute(name, "rows").at(0));
  return rows == 0 ? std::vector<double>() : f.readArray(name);
}

// A list attribute that may be empty (an HDF5 attribute cannot): its length first.
template <class T>
void setList(Hdf5File& f, const std::string& object, const std::string& key, const std::vector<T>& v) {
  std::vector<double> out{double(v.size())};
  out.insert(out.end(), v.begin(), v.end());
  f.setAttribute(object, key, out);
}
template <class T>
std::vector<T> getList(const Hdf5File& f, const std::string& object, const std::string& key, double lo, double hi) {
  const auto v = f.doubleAttribute(object, key);
  GPHR_REQUIRE(!v.empty() && v[0] == double(v.size() - 1), InputError, "attribute '", key, "' of '", object,
               "' is damaged (its first value is not its length)");
  return wholeNumbers<T>(std::vector<double>(v.begin() + 1, v.end()), "attribute '" + key + "' of '" + object + "'",
                         lo, hi);
}

void writeProvenance(Hdf5File& f, const ReducedModelData& d) {
  f.setAttribute("/", "format", std::string(kFormat));
  f.setAttribute("/", "schema_version", std::vector<double>{double(d.schemaVersion)});
  f.setAttribute("/", "scene", d.sceneName);
  f.setAttribute("/", "scene_config", d.sceneConfig);
  f.setAttribute("/", "integrator_config", d.integratorConfig);
  f.setAttribute("/", "config", d.config);
  f.setAttribute("/", "gphr_version", d.gphrVersion);
  f.setAttribute("/", "trilinos_version", d.trilinosVersion);
  f.setAttribute("/", "created", d.created);
  f.setAttribute("/", "build_ranks", std::vector<double>{double(d.buildRanks)});
  f.setAttribute("/", "offline_seconds", std::vector<double>{d.offlineSeconds});
  f.setAttribute("/", "cached_stages", joined(d.cachedStages));
  f.setAttribute("/", "time", std::vector<double>{d.T, d.dt});
  f.setAttribute("/", "polynomial_degree", std::vector<double>{double(d.polynomialDegree)});
  f.setAttribute("/", "target_error", std::vector<double>{d.targetError});
  if (!d.queryDefaults.empty()) {  // "method k=K m=M;..." and per default: estimated, verified max, met
    std::string names;
    std::vector<double> errors;
    for (const auto& q : d.queryDefaults) {
      names += (names.empty() ? "" : ";") + queryDefaultText(q);
      errors.insert(errors.end(), {q.estimatedMax, q.verifiedMax, q.met ? 1.0 : 0.0});
    }
    f.setAttribute("/", "query_defaults", names);
    f.setAttribute("/", "query_default_errors", errors);
  }
  f.setAttribute("/", "parameter_names", joined(d.parameterNames));
  std::vector<double> lower, upper, enters;
  for (size_t p = 0; p < d.box.size(); ++p)
    lower.push_back(d.box[p].first), upper.push_back(d.box[p].second), enters.push_back(d.enters.at(p));
  if (!d.greedy.empty()) {  // rows: full solves, largest estimate, the point added (NaN: none)
    std::vector<double> rows;
    std::string models;
    for (const auto& r : d.greedy) {
      rows.push_back(double(r.fullSolves)), rows.push_back(r.maxEstimate);
      for (size_t p = 0; p < d.box.size(); ++p) rows.push_back(r.added.empty() ? NAN : r.added.at(p));
      models += (models.empty() ? "" : ";") + r.model;
    }
    f.writeArray("/greedy", rows, d.greedy.size(), 2 + d.box.size());
    f.setAttribute("/greedy", "models", models);
    f.setAttribute("/greedy", "layout", std::string("per round: training points, the best model's largest estimated "
                                                    "E_L2 over the candidates, the parameter added next (NaN: none)"));
  }
  if (!d.trainingParameters.empty() && !d.box.empty()) {  // the training parameters, one per row
    std::vector<double> rows;
    for (const auto& mu : d.trainingParameters) rows.insert(rows.end(), mu.begin(), mu.end());
    f.writeArray("/training_parameters", rows, d.trainingParameters.size(), d.box.size());
  }
  f.setAttribute("/", "box_lower", lower);
  f.setAttribute("/", "box_upper", upper);
  f.setAttribute("/", "parameter_enters", enters);
}

// A row sample's datasets in group g (the reference is never stored: it is interpolated).
void writeRowSample(Hdf5File& f, const std::string& g, const RowSample& s) {
  f.writeArray(g + "/rows", toDoubles(s.rows), s.rows.size(), 1);
  f.writeArray(g + "/weights", s.weights, s.weights.size(), 1);
  f.writeArray(g + "/stencil_offsets", toDoubles(s.stencil.offsets), s.stencil.offsets.size(), 1);
  f.writeArray(g + "/stencil_gids", toDoubles(s.stencil.gids), s.stencil.gids.size(), 1);
  f.writeArray(g + "/basis_rows", s.basisRows, s.stencil.gids.size(), static_cast<size_t>(s.reducedDim));
  f.setAttribute(g, "shifted", std::vector<double>{s.shifted ? 1.0 : 0.0});
}

// The error indicator's sample of a basis group g (none written when it is empty).
void writeIndicator(Hdf5File& f, const std::string& g, const IndicatorRows& x) {
  if (x.empty()) return;
  const std::string gi = g + "/indicator";
  f.createGroup(gi);
  f.writeArray(gi + "/entries", toDoubles(x.entries), x.entries.size(), 1);
  f.writeArray(gi + "/basis_rows", x.basisRows, x.entries.size(), static_cast<size_t>(x.terms.reducedDim));
  f.setAttribute(gi, "terms", std::vector<double>{double(x.terms.rows.size())});
  if (!x.terms.rows.empty()) {
    f.createGroup(gi + "/terms");
    writeRowSample(f, gi + "/terms", x.terms);
  }
}

void writeBasisData(Hdf5File& f, const StoredBasisData& b, const RCP<const MultiVector>& A, const PhaseSpace* space) {
  const std::string g = basisGroup(b.k);
  const size_t r = 2 * static_cast<size_t>(b.k);
  f.createGroup(g);
  f.setAttribute(g, "k", std::vector<double>{double(b.k)});
  writeMatrix(f, g + "/reference_gids", toDoubles(b.referenceGids), b.referenceGids.size(), 1);
  const auto& I = b.interpolant;
  f.writeArray(g + "/interpolation_values", I.values(), I.numNodes(), I.valuesPerNode());
  setList(f, g + "/interpolation_values", "nodes_per_parameter", I.nodesPerParameter());
  setList(f, g + "/interpolation_values", "interpolated_parameters", b.interpolated);
  f.setAttribute(g + "/interpolation_values", "layout",
                 std::string("per node (Chebyshev-Lobatto tensor grid over interpolated_parameters, last one "
                             "fastest; one node if none): L_r (2k x 2k, column-major), f_r (2k), y0 at reference_gids, "
                             "then the error indicator's rows of L A (s x 2k, row-major) and f (s)"));
  const auto& C = b.constant;
  f.writeArray(g + "/constant_values", C.values(), C.numNodes(), 1);
  setList(f, g + "/constant_values", "nodes_per_parameter", C.nodesPerParameter());
  f.setAttribute(g + "/constant_values", "layout",
                 std::string("c = H(y0) per node of the tensor grid over every parameter (last one fastest)"));
  for (const auto& [piece, err] : b.interpolationError)
    f.setAttribute(g + "/interpolation_values", "error_" + piece, std::vector<double>{err});
  writeMatrix(f, g + "/probe_gids", toDoubles(b.probeGids), b.probeGids.size(), 1);
  writeMatrix(f, g + "/probe_rows", b.probeRows, b.probeGids.size(), r);
  writeIndicator(f, g, b.indicator);
  if (A.is_null()) return;
  f.writeStates(g + "/basis", *A, *space);
  f.setAttribute(g + "/basis", "fingerprint", columnFingerprint(*A));  // the basis is outside the checksum
}

void writeModel(Hdf5File& f, const StoredHyperModel& m) {
  const std::string g = basisGroup(m.k) + "/" + m.method, gm = g + "/m" + std::to_string(m.m);
  if (!f.exists(g)) f.createGroup(g);
  f.createGroup(gm);
  if (m.onlineNeedsFullSystem()) {
    f.setAttribute(gm, "adeim_config", m.adeimConfig);
    f.setAttribute(gm, "online", std::string("the full system at the query's parameter, on every rank (needs /k<k>/basis)"));
    const IndicatorCalibration& c = m.calibration;
    f.setAttribute(gm, "indicator_calibration", std::vector<double>{c.scale, c.exponent, double(c.points), c.worstFactor});
    return;
  }
  writeRowSample(f, gm, m.sample);
  f.setAttribute(gm, "cond_PtU", std::vector<double>{m.conditionNumber});
  const IndicatorCalibration& c = m.calibration;
  f.setAttribute(gm, "indicator_calibration", std::vector<double>{c.scale, c.exponent, double(c.points), c.worstFactor});
}

// The root attributes, each of its type and range.
void readProvenance(const Hdf5File& f, ReducedModelData& d) {
  d.sceneName = f.stringAttribute("/", "scene");
  d.sceneConfig = f.stringAttribute("/", "scene_config");
  d.integratorConfig = f.stringAttribute("/", "integrator_config");
  d.config = f.stringAttribute("/", "config");
  d.gphrVersion = f.stringAttribute("/", "gphr_version");
  d.trilinosVersion = f.stringAttribute("/", "trilinos_version");
  d.created = f.stringAttribute("/", "created");
  GPHR_REQUIRE(!d.sceneName.empty() && !d.integratorConfig.empty(), InputError,
               "attribute 'scene' or 'integrator_config' is empty");
  d.buildRanks = static_cast<int>(wholeAttribute(f, "/", "build_ranks", 1, 1e9));
  d.offlineSeconds = f.doubleAttribute("/", "offline_seconds").at(0);
  const auto time = finite(f.doubleAttribute("/", "time"), "attribute 'time'");
  GPHR_REQUIRE(time.size() == 2 && time[1] > 0 && time[0] >= time[1], InputError, "attribute 'time' (T, dt) is not "
               "two numbers with dt > 0 and T >= dt");
  d.T = time[0], d.dt = time[1];
  d.polynomialDegree = static_cast<int>(wholeAttribute(f, "/", "polynomial_degree", 0, 64));
  const auto target = f.doubleAttribute("/", "target_error");
  GPHR_REQUIRE(target.size() == 1 && std::isfinite(target[0]) && target[0] >= 0.0, InputError,
               "attribute 'target_error' is not one finite number >= 0 (0: no target)");
  d.targetError = target[0];
  d.parameterNames = split(f.stringAttribute("/", "parameter_names"), ',');
  const auto lo = finite(f.doubleAttribute("/", "box_lower"), "attribute 'box_lower'");
  const auto hi = finite(f.doubleAttribute("/", "box_upper"), "attribute 'box_upper'");
  d.enters = wholeNumbers<unsigned>(f.doubleAttribute("/", "parameter_enters"), "attribute 'parameter_enters'", 0, 7);
  GPHR_REQUIRE(lo.size() == d.parameterNames.size() && hi.size() == lo.size() && d.enters.size() == lo.size(),
               InputError, "the parameter box is inconsistent (", d.parameterNames.size(), " names, ", lo.size(),
               " lower and ", hi.size(), " upper bounds, ", d.enters.size(), " entry flags)");
  for (size_t p = 0; p < lo.size(); ++p) {
    GPHR_REQUIRE(lo[p] <= hi[p] && !d.parameterNames[p].empty(), InputError, "parameter ", p, " ('",
                 d.parameterNames[p], "') has the box [", lo[p], ", ", hi[p], "]; allowed: a name and lower <= upper");
    d.box.emplace_back(lo[p], hi[p]);
  }
  if (f.hasAttribute("/", "cached_stages")) d.cachedStages = split(f.stringAttribute("/", "cached_stages"), ',');
  if (f.exists("/training_parameters")) {
    size_t rows = 0, cols = 0;
    const auto v = f.readArray("/training_parameters", &rows, &cols);
    GPHR_REQUIRE(cols == d.box.size() && rows <= 1000000, InputError, "/training_parameters is ", rows, " x ", cols,
                 "; allowed: points x ", d.box.size(), " (one value per parameter)");
    for (size_t i = 0; i < rows; ++i) {
      d.trainingParameters.emplace_back(v.begin() + i * cols, v.begin() + (i + 1) * cols);
      for (double x : d.trainingParameters.back())
        GPHR_REQUIRE(std::isfinite(x), InputError, "/training_parameters row ", i, " holds ", x, "; allowed: finite values");
    }
  }
  if (f.exists("/greedy")) {
    size_t rows = 0, cols = 0;
    const auto v = f.readArray("/greedy", &rows, &cols);
    const auto models = split(f.stringAttribute("/greedy", "models"), ';');
    GPHR_REQUIRE(cols == 2 + d.box.size() && models.size() == rows, InputError, "/greedy is ", rows, " x ", cols,
                 " with ", models.size(), " model names; allowed: rounds x ", 2 + d.box.size(), ", a name per round");
    for (size_t i = 0; i < rows; ++i) {
      TrainingRound r;
      r.fullSolves = static_cast<long>(v[i * cols]), r.maxEstimate = v[i * cols + 1], r.model = models[i];
      if (std::isfinite(v[i * cols + 2])) r.added.assign(v.begin() + i * cols + 2, v.begin() + (i + 1) * cols);
      d.greedy.push_back(r);
    }
  }
}

struct ModelKey {
  std::string method;
  int k, m;
};

// "method/k<k>/m<m>", with k and m whole numbers in range.
ModelKey parseModelKey(const std::string& key) {
  const auto a = key.find('/'), b = key.rfind('/');
  const auto whole = [&](const std::string& text, char tag) {
    GPHR_REQUIRE(text.size() >= 2 && text.size() <= 7 && text[0] == tag &&
                     text.find_first_not_of("0123456789", 1) == std::string::npos,
                 InputError, "attribute 'models' has entry '", key, "'; allowed: method/k<k>/m<m>");
    const int v = std::stoi(text.substr(1));
    GPHR_REQUIRE(v >= 1 && v <= kMaxReducedSize, InputError, "attribute 'models' has entry '", key, "' with ", tag,
                 " = ", v, "; allowed: 1 to ", kMaxReducedSize);
    return v;
  };
  GPHR_REQUIRE(a != std::string::npos && b != a && a > 0 && key.find('/', a + 1) == b, InputError,
               "attribute 'models' has entry '", key, "'; allowed: method/k<k>/m<m>");
  const std::string method = key.substr(0, a);
  GPHR_REQUIRE(isMethod(method) && methodInfo(method).storable, InputError, "attribute 'models' has entry '", key,
               "' of method '", method, "', which no model file holds; allowed: ",
               methodNames([](const MethodInfo& info) { return info.storable; }));
  return ModelKey{method, whole(key.substr(a + 1, b - a - 1), 'k'), whole(key.substr(b + 1), 'm')};
}

// A row sample's datasets in group g (writeRowSample), whole and consistent; reducedDim 2k.
RowSample readRowSample(const Hdf5File& f, const std::string& g, int k) {
  RowSample s;
  s.rows = wholeNumbers<GO>(f.readArray(g + "/rows"), g + "/rows", 0, kMaxIndex);
  {
    auto sorted = s.rows;  // in the order DEIM chose them, each once
    std::sort(sorted.begin(), sorted.end());
    GPHR_REQUIRE(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end(), InputError, g,
                 "/rows names a term twice; allowed: each term once");
  }
  s.weights = finite(f.readArray(g + "/weights"), g + "/weights");
  s.stencil.offsets = wholeNumbers<size_t>(f.readArray(g + "/stencil_offsets"), g + "/stencil_offsets", 0, kMaxIndex);
  s.stencil.gids = wholeNumbers<GO>(f.readArray(g + "/stencil_gids"), g + "/stencil_gids", 0, kMaxIndex);
  s.basisRows = finite(f.readArray(g + "/basis_rows"), g + "/basis_rows");
  s.reducedDim = 2 * k;
  s.shifted = wholeAttribute(f, g, "shifted", 0, 1) != 0;
  GPHR_REQUIRE(!s.rows.empty() && s.weights.size() == s.rows.size() && s.stencil.offsets.size() == s.rows.size() + 1 &&
                   s.basisRows.size() == s.stencil.gids.size() * s.reducedDim,
               InputError, g, " is inconsistent: ", s.rows.size(), " rows (allowed: at least 1), ", s.weights.size(),
               " weights, ", s.stencil.offsets.size(), " stencil offsets (rows + 1), ", s.basisRows.size(),
               " basis-row values (stencil entries x 2k = ", s.stencil.gids.size() * s.reducedDim, ")");
  const auto& off = s.stencil.offsets;
  GPHR_REQUIRE(off.front() == 0 && off.back() == s.stencil.gids.size(), InputError, g, "/stencil_offsets runs from ",
               off.front(), " to ", off.back(), "; allowed: from 0 to the ", s.stencil.gids.size(), " stencil entries");
  for (size_t i = 1; i < off.size(); ++i)
    GPHR_REQUIRE(off[i - 1] < off[i], InputError, g, "/stencil_offsets is not increasing at entry ", i, " (",
                 off[i - 1], ", ", off[i], "): every row has at least one stencil entry");
  return s;
}

void requireReferenced(const std::vector<GO>& gids, const StoredBasisData& basis, const std::string& what) {
  for (GO gid : gids)
    GPHR_REQUIRE(std::binary_search(basis.referenceGids.begin(), basis.referenceGids.end(), gid), InputError, what,
                 " names state entry ", gid, ", which has no reference value in /k", basis.k, "/reference_gids");
}

// The error indicator's sample of basis group g (none: empty), its entries pairs (q_i, p_i).
IndicatorRows readIndicator(const Hdf5File& f, const std::string& g, int k) {
  IndicatorRows x;
  const std::string gi = g + "/indicator";
  if (!f.exists(gi)) return x;
  x.entries = wholeNumbers<GO>(f.readArray(gi + "/entries"), gi + "/entries", 0, kMaxIndex);
  requireAscending(x.entries, gi + "/entries");
  const size_t s = x.entries.size(), h = s / 2;
  GPHR_REQUIRE(s >= 2 && s % 2 == 0, InputError, gi, "/entries holds ", s, " entries; allowed: an even number >= 2");
  for (size_t i = 1; i < h; ++i)
    GPHR_REQUIRE(x.entries[i + h] - x.entries[i] == x.entries[h] - x.entries[0], InputError, gi, "/entries: entry ",
                 i + h, " is not the partner p_i of entry ", i, " (q entries first, then their p entries)");
  x.basisRows = finite(f.readArray(gi + "/basis_rows"), gi + "/basis_rows");
  GPHR_REQUIRE(x.basisRows.size() == s * 2 * static_cast<size_t>(k), InputError, gi, "/basis_rows has ",
               x.basisRows.size(), " values; allowed: ", s, " entries x 2k = ", s * 2 * k);
  const long terms = wholeAttribute(f, gi, "terms", 0, kMaxIndex);
  if (terms > 0) x.terms = readRowSample(f, gi + "/terms", k);
  GPHR_REQUIRE(x.terms.rows.size() == static_cast<size_t>(terms), InputError, gi, " names ", terms, " terms and holds ",
               x.terms.rows.size());
  x.terms.reducedDim = 2 * k;
  return x;
}

IndicatorCalibration readCalibration(const Hdf5File& f, const std::string& gm) {
  const auto v = f.doubleAttribute(gm, "indicator_calibration");
  GPHR_REQUIRE(v.size() == 4 && std::isfinite(v[0]) && v[0] >= 0.0 && std::isfinite(v[1]) && v[1] >= 0.5 &&
                   v[1] <= 2.0 && v[2] >= 0.0 && v[2] <= 1e9 && v[2] == std::floor(v[2]) && std::isfinite(v[3]) &&
                   v[3] >= 0.0,
               InputError, "attribute 'indicator_calibration' of '", gm,
               "' is not [scale >= 0, exponent in [0.5, 2], points >= 0, worst factor >= 0]");
  IndicatorCalibration c;
  c.scale = v[0], c.exponent = v[1], c.points = static_cast<int>(v[2]), c.worstFactor = v[3];
  return c;
}

StoredBasisData readBasisData(const Hdf5File& f, const ReducedModelData& d, int k) {
  StoredBasisData b;
  b.k = k;
  const std::string g = basisGroup(k), iv = g + "/interpolation_values", cv = g + "/constant_values";
  const size_t r = 2 * static_cast<size_t>(k);
  b.referenceGids = wholeNumbers<GO>(readMatrix(f, g + "/reference_gids"), g + "/reference_gids", 0, kMaxIndex);
  requireAscending(b.referenceGids, g + "/reference_gids");
  b.interpolated = getList<size_t>(f, iv, "interpolated_parameters", 0, double(d.box.size()) - 1);
  requireAscending(b.interpolated, "attribute 'interpolated_parameters' of '" + iv + "'");
  std::vector<std::pair<double, double>> box;
  for (size_t p : b.interpolated) box.push_back(d.box.at(p));
  const auto nodes = getList<int>(f, iv, "nodes_per_parameter", 1, kMaxNodes);
  const auto cnodes = getList<int>(f, cv, "nodes_per_parameter", 1, kMaxNodes);
  GPHR_REQUIRE(nodes.size() == b.interpolated.size() && cnodes.size() == d.box.size(), InputError,
               "the interpolants of k = ", k, " have ", nodes.size(), " and ", cnodes.size(),
               " node counts for ", b.interpolated.size(), " and ", d.box.size(), " parameters");
  // sizes are checked against the datasets before the interpolants allocate anything
  size_t rows = 0, cols = 0, crows = 0, ccols = 0;
  const auto values = finite(f.readArray(iv, &rows, &cols), iv), constants = finite(f.readArray(cv, &crows, &ccols), cv);
  size_t numNodes = 1, numConstNodes = 1;
  for (int n : nodes) numNodes *= static_cast<size_t>(n);
  for (int n : cnodes) numConstNodes *= static_cast<size_t>(n);
  b.indicator = readIndicator(f, g, k);
  requireReferenced(b.indicator.entries, b, g + "/indicator/entries");
  requireReferenced(b.indicator.terms.stencil.gids, b, g + "/indicator/terms/stencil_gids");
  GPHR_REQUIRE(rows == numNodes && cols == b.valuesPerNode(), InputError, iv, " is ", rows, " x ", cols, "; allowed: ",
               numNodes, " x ", b.valuesPerNode(), " (nodes x [L_r, f_r, y0 at reference_gids, indicator rows])");
  GPHR_REQUIRE(crows == numConstNodes && ccols == 1, InputError, cv, " is ", crows, " x ", ccols, "; allowed: ",
               numConstNodes, " x 1");
  b.interpolant = ParameterInterpolant(box, nodes, b.valuesPerNode());
  b.interpolant.setValues(values);
  b.constant = ParameterInterpolant(d.box, cnodes, 1);
  b.constant.setValues(constants);
  for (const char* piece : {"L", "f", "c", "reference"})
    if (f.hasAttribute(iv, std::string("error_") + piece))
      b.interpolationError[piece] = f.doubleAttribute(iv, std::string("error_") + piece).at(0);
  b.probeGids = wholeNumbers<GO>(readMatrix(f, g + "/probe_gids"), g + "/probe_gids", 0, kMaxIndex);
  b.probeRows = finite(readMatrix(f, g + "/probe_rows"), g + "/probe_rows");
  GPHR_REQUIRE(b.probeRows.size() == b.probeGids.size() * r, InputError, g, "/probe_rows has ", b.probeRows.size(),
               " values; allowed: ", b.probeGids.size(), " probes x 2k = ", r);
  for (GO gid : b.probeGids)
    GPHR_REQUIRE(std::binary_search(b.referenceGids.begin(), b.referenceGids.end(), gid), InputError, g,
                 "/probe_gids names state entry ", gid, ", which has no reference value in ", g, "/reference_gids");
  b.hasBasis = f.exists(g + "/basis");
  return b;
}

StoredHyperModel readModel(const Hdf5File& f, const StoredBasisData& basis, const std::string& method, int k, int m) {
  StoredHyperModel out;
  out.method = method, out.k = k, out.m = m;
  const std::string gm = basisGroup(k) + "/" + method + "/m" + std::to_string(m);
  out.calibration = readCalibration(f, gm);
  if (out.onlineNeedsFullSystem()) {
    out.adeimConfig = f.stringAttribute(gm, "adeim_config");
    GPHR_REQUIRE(!out.adeimConfig.empty(), InputError, "attribute 'adeim_config' of '", gm, "' is empty");
    return out;
  }
  out.sample = readRowSample(f, gm, k);
  // m is the budget: gp-eqp may stop with fewer terms (no further term improves its fit).
  GPHR_REQUIRE(out.sample.rows.size() <= static_cast<size_t>(m), InputError, "model ", out.key(), " has ",
               out.sample.rows.size(), " rows; allowed: 1 to m = ", m);
  out.conditionNumber = f.doubleAttribute(gm, "cond_PtU").at(0);
  GPHR_REQUIRE(std::isfinite(out.conditionNumber) && out.conditionNumber >= 0, InputError, "attribute 'cond_PtU' of '",
               gm, "' = ", out.conditionNumber, "; allowed: a finite number >= 0");
  requireReferenced(out.sample.stencil.gids, basis, gm + "/stencil_gids");
  return out;
}

RCP<const Comm> selfComm() { return rcp(new Teuchos::SerialComm<int>()); }

}  // namespace

std::string modelDataChecksum(const ReducedModelData& d) {
  Fnv1a h;
  for (const auto& t : {d.sceneName, d.sceneConfig, d.integratorConfig, d.config}) h.text(t);
  h.numbers(std::vector<double>{d.T, d.dt, double(d.polynomialDegree)});
  for (const auto& n : d.parameterNames) h.text(n);
  for (size_t p = 0; p < d.box.size(); ++p) h.numbers(std::vector<double>{d.box[p].first, d.box[p].second});
  h.numbers(d.enters);
  for (const auto& b : d.bases) {
    h.number(b.k);
    h.numbers(b.referenceGids);
    h.numbers(b.interpolated);
    h.numbers(b.interpolant.nodesPerParameter());
    h.numbers(b.interpolant.values());
    h.numbers(b.constant.nodesPerParameter());
    h.numbers(b.constant.values());
    h.numbers(b.probeGids);
    h.numbers(b.probeRows);
    const IndicatorRows& x = b.indicator;
    h.numbers(x.entries);
    h.numbers(x.basisRows);
    h.numbers(x.terms.rows);
    h.numbers(x.terms.weights);
    h.numbers(x.terms.stencil.offsets);
    h.numbers(x.terms.stencil.gids);
    h.numbers(x.terms.basisRows);
  }
  h.number(d.targetError);
  for (const auto& q : d.queryDefaults) {  // none: nothing added (files without defaults verify as before)
    h.text(queryDefaultText(q));
    h.numbers(std::vector<double>{q.estimatedMax, q.verifiedMax, q.met ? 1.0 : 0.0});
  }
  for (const auto& m : d.models) {
    h.text(m.key());
    const IndicatorCalibration& c = m.calibration;
    h.numbers(std::vector<double>{c.scale, c.exponent, double(c.points), c.worstFactor});
    if (m.onlineNeedsFullSystem()) {  // stored as its options
      h.text(m.adeimConfig);
      continue;
    }
    h.numbers(m.sample.rows);
    h.numbers(m.sample.weights);
    h.numbers(m.sample.stencil.offsets);
    h.numbers(m.sample.stencil.gids);
    h.numbers(m.sample.basisRows);
    h.numbers(std::vector<double>{m.sample.shifted ? 1.0 : 0.0, m.conditionNumber});
  }
  return h.hex();
}

std::vector<double> StoredBasisData::restrict(const std::vector<double>& mu) const {
  std::vector<double> sub;
  for (size_t p : interpolated) sub.push_back(mu.at(p));
  return sub;
}

OnlineParameterData StoredBasisData::at(const std::vector<double>& mu) const {
  const auto v = interpolant.evaluate(restrict(mu));
  const int r = 2 * k;
  OnlineParameterData out;
  out.linear.L.shape(r, r);
  out.linear.f.size(r);
  size_t i = 0;
  for (int c = 0; c < r; ++c)
    for (int row = 0; row < r; ++row) out.linear.L(row, c) = v[i++];
  for (int row = 0; row < r; ++row)  // symmetric to the last bit, as reduceLinearPart makes it
    for (int c = row + 1; c < r; ++c) out.linear.L(row, c) = out.linear.L(c, row) = 0.5 * (out.linear.L(row, c) + out.linear.L(c, row));
  for (int row = 0; row < r; ++row) out.linear.f(row) = v[i++];
  out.linear.c = constant.evaluate(mu).at(0);
  out.reference.assign(v.begin() + i, v.begin() + i + referenceGids.size());
  i += referenceGids.size();
  const size_t s = indicator.entries.size();
  out.indicator.LA.assign(v.begin() + i, v.begin() + i + s * r);
  out.indicator.f.assign(v.begin() + i + s * r, v.end());
  return out;
}

size_t StoredBasisData::valuesPerNode() const {
  const size_t r = 2 * static_cast<size_t>(k), s = indicator.entries.size();
  return r * r + r + referenceGids.size() + s * (r + 1);
}

std::vector<double> StoredBasisData::pack(const OnlineParameterData& d) const {
  const int r = 2 * k;
  const size_t s = indicator.entries.size();
  GPHR_REQUIRE(d.linear.L.numRows() == r && d.reference.size() == referenceGids.size() &&
                   d.indicator.LA.size() == s * r && d.indicator.f.size() == s,
               InputError, "reduced-model file: node data of 2k = ", d.linear.L.numRows(), ", ", d.reference.size(),
               " reference entries and ", d.indicator.f.size(), " indicator rows for 2k = ", r, ", ",
               referenceGids.size(), " and ", s);
  std::vector<double> v;
  for (int c = 0; c < r; ++c)
    for (int row = 0; row < r; ++row) v.push_back(d.linear.L(row, c));
  for (int row = 0; row < r; ++row) v.push_back(d.linear.f(row));
  v.insert(v.end(), d.reference.begin(), d.reference.end());
  v.insert(v.end(), d.indicator.LA.begin(), d.indicator.LA.end());
  v.insert(v.end(), d.indicator.f.begin(), d.indicator.f.end());
  return v;
}

const StoredBasisData& ReducedModelData::basis(int k) const {
  std::string held;
  for (const auto& b : bases) {
    if (b.k == k) return b;
    held += (held.empty() ? "" : ", ") + std::to_string(b.k);
  }
  throw InputError(detail::concat("k = ", k, " is not in the reduced-model file; it holds k = ", held));
}

const StoredHyperModel& ReducedModelData::model(const std::string& method, int k, int m) const {
  for (const auto& x : models)
    if (x.method == method && x.k == k && x.m == m) return x;
  throw InputError(detail::concat("model ", method, " k=", k, " m=", m, " is not in the reduced-model file; it holds ",
                                  modelList()));
}

bool ReducedModelData::outsideBox(const std::vector<double>& mu) const {
  for (size_t p = 0; p < mu.size() && p < box.size(); ++p)
    if (mu[p] < box[p].first || mu[p] > box[p].second) return true;
  return false;
}

const QueryDefault* ReducedModelData::queryDefault(const std::string& method) const {
  for (const auto& q : queryDefaults)
    if (q.method == method) return &q;
  return nullptr;
}

std::string ReducedModelData::modelList() const {
  std::string s;
  for (const auto& x : models)
    s += (s.empty() ? "" : ", ") + x.method + " k=" + std::to_string(x.k) + " m=" + std::to_string(x.m);
  return s.empty() ? "no model" : s;
}

void writeReducedModelFile(const std::string& path, const RCP<const Comm>& comm, const ReducedModelData& data,
                           const std::vector<RCP<const MultiVector>>& bases, const PhaseSpace* space) {
  GPHR_REQUIRE(bases.size() == data.bases.size(), InputError, "reduced-model file: ", bases.size(),
               " basis slots for ", data.bases.size(), " bases");
  for (const auto& A : bases)
    GPHR_REQUIRE(A.is_null() || space, InputError, "reduced-model file: a basis needs its phase space");
  RenameOnCommit out(path, comm);
  {
    Hdf5File f(out.tempPath(), comm, Hdf5File::Mode::Create);
    writeProvenance(f, data);
    for (size_t i = 0; i < data.bases.size(); ++i) writeBasisData(f, data.bases[i], bases[i], space);
    for (const auto& m : data.models) writeModel(f, m);
    std::string list;
    for (const auto& m : data.models) list += (list.empty() ? "" : ";") + m.key();
    f.setAttribute("/", "models", list);
    f.setAttribute("/", "checksum", modelDataChecksum(data));
    f.flush();
  }
  out.commit();
}

namespace {

// The query defaults (attributes query_defaults, query_default_errors; absent: none), each a model
// the file holds, at most one per method.
void readQueryDefaults(const Hdf5File& f, ReducedModelData& d) {
  if (!f.hasAttribute("/", "query_defaults")) return;
  const auto names = split(f.stringAttribute("/", "query_defaults"), ';');
  const auto errors = f.doubleAttribute("/", "query_default_errors");
  GPHR_REQUIRE(errors.size() == 3 * names.size(), InputError, "attribute 'query_default_errors' has ", errors.size(),
               " numbers for ", names.size(), " query defaults; allowed: 3 per default");
  for (size_t i = 0; i < names.size(); ++i) {
    QueryDefault q;
    char method[32] = {0};
    int consumed = 0;
    GPHR_REQUIRE(std::sscanf(names[i].c_str(), "%31s k=%d m=%d%n", method, &q.k, &q.m, &consumed) == 3 &&
                     consumed == static_cast<int>(names[i].size()),
                 InputError, "query default '", names[i], "'; allowed: 'METHOD k=K m=M'");
    q.method = method;
    d.model(q.method, q.k, q.m);  // InputError naming the models held
    GPHR_REQUIRE(!d.queryDefault(q.method), InputError, "two query defaults for ", q.method);
    q.estimatedMax = errors[3 * i], q.verifiedMax = errors[3 * i + 1], q.met = errors[3 * i + 2] != 0.0;
    d.queryDefaults.push_back(q);
  }
}

// The model data of an open file, validated whole (readReducedModelFile's contract).
ReducedModelData readModelData(const Hdf5File& f) {
  GPHR_REQUIRE(f.hasAttribute("/", "format") && f.stringAttribute("/", "format") == kFormat, InputError,
               "not a gphr reduced-model file (no format attribute '", kFormat, "'; write one with gphr build)");
  ReducedModelData d;
  d.schemaVersion = static_cast<int>(wholeAttribute(f, "/", "schema_version", 0, 1e6));
  GPHR_REQUIRE(d.schemaVersion == kReducedModelSchema, InputError, "schema version ", d.schemaVersion,
               "; this gphr reads schema version ", kReducedModelSchema, " (rebuild the model with this gphr build)");
  readProvenance(f, d);
  const std::string list = f.stringAttribute("/", "models");
  for (const auto& key : split(list, ';')) {  // method/k<k>/m<m>
    const auto [method, k, m] = parseModelKey(key);
    GPHR_REQUIRE(f.exists(basisGroup(k) + "/" + method + "/m" + std::to_string(m)), InputError, "attribute 'models' "
                 "names ", key, ", which the file does not hold");
    if (std::none_of(d.bases.begin(), d.bases.end(), [&](const StoredBasisData& x) { return x.k == k; }))
      d.bases.push_back(readBasisData(f, d, k));
    GPHR_REQUIRE(std::none_of(d.models.begin(), d.models.end(), [&](const StoredHyperModel& x) { return x.key() == key; }),
                 InputError, "attribute 'models' names ", key, " twice");
    d.models.push_back(readModel(f, d.basis(k), method, k, m));
  }
  GPHR_REQUIRE(!d.models.empty(), InputError, "it holds no model (attribute 'models' is empty)");
  readQueryDefaults(f, d);
  // a changed byte anywhere in the model data is an error, not a different model
  GPHR_REQUIRE(f.hasAttribute("/", "checksum"), InputError, "it has no checksum attribute (write it with gphr build)");
  const std::string stored = f.stringAttribute("/", "checksum"), computed = modelDataChecksum(d);
  GPHR_REQUIRE(stored == computed, InputError, "its model data do not match its checksum (stored ", stored,
               ", computed ", computed, "): the file was changed or damaged after gphr build wrote it");
  d.checksum = stored;
  return d;
}

}  // namespace

OpenModelFile::Stamp OpenModelFile::stampOf(int fd) {
  struct stat st {};
  GPHR_REQUIRE(::fstat(fd, &st) == 0, InputError, "cannot stat the open file: ", std::strerror(errno));
  Stamp s;
  s.device = st.st_dev, s.inode = st.st_ino, s.size = static_cast<long long>(st.st_size);
  s.modifiedNs = static_cast<long long>(st.st_mtim.tv_sec) * 1000000000LL + st.st_mtim.tv_nsec;
  return s;
}

OpenModelFile::OpenModelFile(const std::string& path) : path_(path) {
  try {
    // The descriptor first, then HDF5's open of the same path: if the path was replaced in
    // between (their inodes differ), open both again, so that the stamp is the HDF5 file's.
    for (int attempt = 0;; ++attempt) {
      fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
      file_ = std::make_unique<Hdf5File>(path, selfComm(), Hdf5File::Mode::ReadOnly);
      GPHR_REQUIRE(fd_ >= 0, InputError, "cannot open it: ", std::strerror(errno));
      opened_ = stampOf(fd_);
      struct stat now {};
      if (::stat(path.c_str(), &now) == 0 && now.st_ino == opened_.inode && now.st_dev == opened_.device) break;
      GPHR_REQUIRE(attempt < 3, InputError, "it was replaced at every one of 4 attempts to open it");
      file_.reset();
      ::close(fd_);
    }
    data_ = readModelData(*file_);
    requireUnchanged();  // not rewritten in place while it was read
  } catch (const InputError& e) {
    if (fd_ >= 0) ::close(fd_);
    throw InputError(detail::concat("reduced-model file '", path, "': ", e.what()));
  } catch (const std::logic_error& e) {  // .at() of a damaged attribute
    if (fd_ >= 0) ::close(fd_);
    throw InputError(detail::concat("reduced-model file '", path, "' is damaged: ", e.what()));
  }
}

OpenModelFile::~OpenModelFile() {
  file_.reset();
  if (fd_ >= 0) ::close(fd_);
}

void OpenModelFile::requireUnchanged() const {
  GPHR_REQUIRE(stampOf(fd_) == opened_, InputError, "it was changed in place while in use (its size or modification "
               "time differ from those when it was opened); allowed: a model file left as it is while gphr reads it, "
               "or replaced whole (gphr build writes a new file and renames it over the old)");
}

ReducedModelData readReducedModelFile(const std::string& path) { return OpenModelFile(path).data(); }

RCP<MultiVector> OpenModelFile::basis(int k, const PhaseSpace& space) const {
  const std::string name = basisGroup(k) + "/basis";
  RCP<MultiVector> A;
  std::vector<double> fingerprint;  // read with the basis, under one lock and one stamp check
  int bad = 0;
  {
    const std::lock_guard<std::mutex> lock(read_);
    try {
      requireUnchanged();
    } catch (const InputError& e) {
      throw InputError(detail::concat("reduced-model file '", path_, "': ", e.what()));
    }
    GPHR_REQUIRE(file_->exists(name), InputError, "reduced-model file '", path_, "' holds no basis for k = ", k,
                 " (build it with build.withBasis: true)");
    A = file_->readStates(name, space);
    GPHR_REQUIRE(A->getNumVectors() == 2 * static_cast<size_t>(k), InputError, "reduced-model file '", path_, "': ",
                 name, " has ", A->getNumVectors(), " columns; allowed: 2k = ", 2 * k);
    if (file_->hasAttribute(name, "fingerprint")) fingerprint = file_->doubleAttribute(name, "fingerprint");
    auto a = A->getLocalViewHost(Tpetra::Access::ReadOnly);
    for (size_t j = 0; j < a.extent(1) && !bad; ++j)
      for (size_t i = 0; i < a.extent(0) && !bad; ++i) bad = !std::isfinite(a(i, j));
  }
  int anyBad = 0;
  Teuchos::reduceAll(*space.comm(), Teuchos::REDUCE_MAX, bad, Teuchos::outArg(anyBad));
  GPHR_REQUIRE(!anyBad, InputError, "reduced-model file '", path_, "': ", name, " holds a value that is not finite; "
               "allowed: finite values (the file is damaged: build it again)");
  // The basis is outside the file's checksum (distributed, and read only to lift): its
  // fingerprint catches a changed value (ColumnFingerprint.hpp; ||a_j|| = 1). Files written
  // before the fingerprint have none: only the checks above apply to them.
  if (!fingerprint.empty())
    GPHR_REQUIRE(fingerprintMatches(fingerprint, *A), InputError, "reduced-model file '", path_, "': ", name,
                 " does not match its fingerprint (a changed value; the file is damaged: build it again)");
  return A;
}

}  // namespace gphr
