#include "gphr/hyper/ReducedModelFile.hpp"

#include <Teuchos_DefaultSerialComm.hpp>

#include <algorithm>
#include <sstream>

#include "gphr/core/Error.hpp"
#include "gphr/io/Hdf5File.hpp"

namespace gphr {

namespace {

const char* kFormat = "gphr reduced model";

std::vector<double> toDoubles(const std::vector<GO>& v) { return std::vector<double>(v.begin(), v.end()); }
std::vector<double> toDoubles(const std::vector<size_t>& v) { return std::vector<double>(v.begin(), v.end()); }
template <class T>
std::vector<T> fromDoubles(const std::vector<double>& v) {
  std::vector<T> out;
  for (double x : v) out.push_back(static_cast<T>(x));
  return out;
}

std::string basisGroup(int k) { return "/k" + std::to_string(k); }

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
std::vector<T> getList(const Hdf5File& f, const std::string& object, const std::string& key) {
  const auto v = f.doubleAttribute(object, key);
  GPHR_REQUIRE(!v.empty() && v[0] == double(v.size() - 1), InputError, "attribute '", key, "' of '", object,
               "' is damaged");
  return fromDoubles<T>(std::vector<double>(v.begin() + 1, v.end()));
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
  f.setAttribute("/", "time", std::vector<double>{d.T, d.dt});
  f.setAttribute("/", "polynomial_degree", std::vector<double>{double(d.polynomialDegree)});
  f.setAttribute("/", "parameter_names", joined(d.parameterNames));
  std::vector<double> lower, upper, enters;
  for (size_t p = 0; p < d.box.size(); ++p)
    lower.push_back(d.box[p].first), upper.push_back(d.box[p].second), enters.push_back(d.enters.at(p));
  f.setAttribute("/", "box_lower", lower);
  f.setAttribute("/", "box_upper", upper);
  f.setAttribute("/", "parameter_enters", enters);
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
                             "fastest; one node if none): L_r (2k x 2k, column-major), f_r (2k), y0 at reference_gids"));
  const auto& C = b.constant;
  f.writeArray(g + "/constant_values", C.values(), C.numNodes(), 1);
  setList(f, g + "/constant_values", "nodes_per_parameter", C.nodesPerParameter());
  f.setAttribute(g + "/constant_values", "layout",
                 std::string("c = H(y0) per node of the tensor grid over every parameter (last one fastest)"));
  for (const auto& [piece, err] : b.interpolationError)
    f.setAttribute(g + "/interpolation_values", "error_" + piece, std::vector<double>{err});
  writeMatrix(f, g + "/probe_gids", toDoubles(b.probeGids), b.probeGids.size(), 1);
  writeMatrix(f, g + "/probe_rows", b.probeRows, b.probeGids.size(), r);
  if (!A.is_null()) f.writeStates(g + "/basis", *A, *space);
}

void writeModel(Hdf5File& f, const StoredHyperModel& m) {
  const std::string g = basisGroup(m.k) + "/" + m.method, gm = g + "/m" + std::to_string(m.m);
  if (!f.exists(g)) f.createGroup(g);
  f.createGroup(gm);
  if (m.onlineNeedsFullSystem()) {
    f.setAttribute(gm, "adeim_config", m.adeimConfig);
    f.setAttribute(gm, "online", std::string("the full system at the query's parameter, on every rank (needs /k<k>/basis)"));
    return;
  }
  const RowSample& s = m.sample;
  f.writeArray(gm + "/rows", toDoubles(s.rows), s.rows.size(), 1);
  f.writeArray(gm + "/weights", s.weights, s.weights.size(), 1);
  f.writeArray(gm + "/stencil_offsets", toDoubles(s.stencil.offsets), s.stencil.offsets.size(), 1);
  f.writeArray(gm + "/stencil_gids", toDoubles(s.stencil.gids), s.stencil.gids.size(), 1);
  f.writeArray(gm + "/basis_rows", s.basisRows, s.stencil.gids.size(), static_cast<size_t>(s.reducedDim));
  f.setAttribute(gm, "cond_PtU", std::vector<double>{m.conditionNumber});
  f.setAttribute(gm, "shifted", std::vector<double>{s.shifted ? 1.0 : 0.0});
}

StoredBasisData readBasisData(const Hdf5File& f, const ReducedModelData& d, int k) {
  StoredBasisData b;
  b.k = k;
  const std::string g = basisGroup(k), iv = g + "/interpolation_values", cv = g + "/constant_values";
  b.referenceGids = fromDoubles<GO>(readMatrix(f, g + "/reference_gids"));
  b.interpolated = getList<size_t>(f, iv, "interpolated_parameters");
  std::vector<std::pair<double, double>> box;
  for (size_t p : b.interpolated) box.push_back(d.box.at(p));
  const size_t r = 2 * static_cast<size_t>(k);
  b.interpolant = ParameterInterpolant(box, getList<int>(f, iv, "nodes_per_parameter"),
                                       r * r + r + b.referenceGids.size());
  b.interpolant.setValues(f.readArray(iv));
  b.constant = ParameterInterpolant(d.box, getList<int>(f, cv, "nodes_per_parameter"), 1);
  b.constant.setValues(f.readArray(cv));
  for (const char* piece : {"L", "f", "c", "reference"})
    if (f.hasAttribute(iv, std::string("error_") + piece))
      b.interpolationError[piece] = f.doubleAttribute(iv, std::string("error_") + piece).at(0);
  b.probeGids = fromDoubles<GO>(readMatrix(f, g + "/probe_gids"));
  b.probeRows = readMatrix(f, g + "/probe_rows");
  b.hasBasis = f.exists(g + "/basis");
  return b;
}

StoredHyperModel readModel(const Hdf5File& f, const std::string& method, int k, int m) {
  StoredHyperModel out;
  out.method = method, out.k = k, out.m = m;
  const std::string gm = basisGroup(k) + "/" + method + "/m" + std::to_string(m);
  if (out.onlineNeedsFullSystem()) {
    out.adeimConfig = f.stringAttribute(gm, "adeim_config");
    return out;
  }
  RowSample& s = out.sample;
  s.rows = fromDoubles<GO>(f.readArray(gm + "/rows"));
  s.weights = f.readArray(gm + "/weights");
  s.stencil.offsets = fromDoubles<size_t>(f.readArray(gm + "/stencil_offsets"));
  s.stencil.gids = fromDoubles<GO>(f.readArray(gm + "/stencil_gids"));
  s.basisRows = f.readArray(gm + "/basis_rows");
  s.reducedDim = 2 * k;
  s.shifted = f.doubleAttribute(gm, "shifted").at(0) != 0.0;
  out.conditionNumber = f.doubleAttribute(gm, "cond_PtU").at(0);
  // m is the budget: gp-eqp may stop with fewer terms (no further term improves its fit).
  GPHR_REQUIRE(!s.rows.empty() && s.rows.size() <= static_cast<size_t>(m) && s.weights.size() == s.rows.size() &&
                   s.stencil.offsets.size() == s.rows.size() + 1 && s.stencil.offsets.back() == s.stencil.gids.size() &&
                   s.basisRows.size() == s.stencil.gids.size() * s.reducedDim,
               InputError, "model ", out.key(), " is inconsistent (rows, weights, stencils and basis rows disagree)");
  return out;
}

RCP<const Comm> selfComm() { return rcp(new Teuchos::SerialComm<int>()); }

}  // namespace

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
  out.reference.assign(v.begin() + i, v.end());
  return out;
}

std::vector<double> StoredBasisData::pack(const OnlineParameterData& d) const {
  const int r = 2 * k;
  GPHR_REQUIRE(d.linear.L.numRows() == r && d.reference.size() == referenceGids.size(), InputError,
               "reduced-model file: node data of 2k = ", d.linear.L.numRows(), " and ", d.reference.size(),
               " reference entries for 2k = ", r, " and ", referenceGids.size());
  std::vector<double> v;
  for (int c = 0; c < r; ++c)
    for (int row = 0; row < r; ++row) v.push_back(d.linear.L(row, c));
  for (int row = 0; row < r; ++row) v.push_back(d.linear.f(row));
  v.insert(v.end(), d.reference.begin(), d.reference.end());
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
    f.flush();
  }
  out.commit();
}

ReducedModelData readReducedModelFile(const std::string& path) {
  try {
    Hdf5File f(path, selfComm(), Hdf5File::Mode::ReadOnly);
    GPHR_REQUIRE(f.hasAttribute("/", "format") && f.stringAttribute("/", "format") == kFormat, InputError,
                 "not a gphr reduced-model file (no format attribute '", kFormat, "'; write one with gphr build)");
    ReducedModelData d;
    d.schemaVersion = static_cast<int>(f.doubleAttribute("/", "schema_version").at(0));
    GPHR_REQUIRE(d.schemaVersion == kReducedModelSchema, InputError, "schema version ", d.schemaVersion,
                 "; this gphr reads schema version ", kReducedModelSchema, " (rebuild the model with this gphr build)");
    d.sceneName = f.stringAttribute("/", "scene");
    d.sceneConfig = f.stringAttribute("/", "scene_config");
    d.integratorConfig = f.stringAttribute("/", "integrator_config");
    d.config = f.stringAttribute("/", "config");
    d.gphrVersion = f.stringAttribute("/", "gphr_version");
    d.trilinosVersion = f.stringAttribute("/", "trilinos_version");
    d.created = f.stringAttribute("/", "created");
    d.buildRanks = static_cast<int>(f.doubleAttribute("/", "build_ranks").at(0));
    d.offlineSeconds = f.doubleAttribute("/", "offline_seconds").at(0);
    const auto time = f.doubleAttribute("/", "time");
    d.T = time.at(0), d.dt = time.at(1);
    d.polynomialDegree = static_cast<int>(f.doubleAttribute("/", "polynomial_degree").at(0));
    d.parameterNames = split(f.stringAttribute("/", "parameter_names"), ',');
    const auto lo = f.doubleAttribute("/", "box_lower"), hi = f.doubleAttribute("/", "box_upper");
    d.enters = fromDoubles<unsigned>(f.doubleAttribute("/", "parameter_enters"));
    GPHR_REQUIRE(lo.size() == d.parameterNames.size() && hi.size() == lo.size() && d.enters.size() == lo.size(),
                 InputError, "the parameter box is inconsistent");
    for (size_t p = 0; p < lo.size(); ++p) d.box.emplace_back(lo[p], hi[p]);
    for (const auto& key : split(f.stringAttribute("/", "models"), ';')) {  // method/k<k>/m<m>
      std::string method;
      int k = 0, m = 0;
      const auto a = key.find('/'), b = key.rfind('/');
      method = key.substr(0, a);
      k = std::stoi(key.substr(a + 2, b - a - 2));
      m = std::stoi(key.substr(b + 2));
      if (std::none_of(d.bases.begin(), d.bases.end(), [&](const StoredBasisData& x) { return x.k == k; }))
        d.bases.push_back(readBasisData(f, d, k));
      d.models.push_back(readModel(f, method, k, m));
    }
    return d;
  } catch (const InputError& e) {
    throw InputError(detail::concat("reduced-model file '", path, "': ", e.what()));
  } catch (const std::logic_error& e) {  // std::stoi, .at(): a damaged attribute
    throw InputError(detail::concat("reduced-model file '", path, "' is damaged: ", e.what()));
  }
}

RCP<MultiVector> readReducedModelBasis(const std::string& path, int k, const PhaseSpace& space) {
  Hdf5File f(path, space.comm(), Hdf5File::Mode::ReadOnly);
  const std::string name = basisGroup(k) + "/basis";
  GPHR_REQUIRE(f.exists(name), InputError, "reduced-model file '", path, "' holds no basis for k = ", k,
               " (build it with build.withBasis: true)");
  return f.readStates(name, space);
}

}  // namespace gphr
