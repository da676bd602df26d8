#include "gphr/hyper/EmpiricalQuadrature.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_LAPACK.hpp>
#include <Teuchos_Time.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "gphr/core/CacheKey.hpp"
#include "gphr/core/Error.hpp"
#include "gphr/core/ParameterValidation.hpp"
#include "gphr/core/IndexHash.hpp"
#include "gphr/hyper/JacobianSnapshots.hpp"
#include "gphr/reduction/Deim.hpp"

namespace gphr {

namespace {

// Rows of C per training state: the 2k entries of A^T grad G_e, and the energy row if asked for.
int rowsPerState(int r, const QuadratureOptions& o) { return r + (o.energyWeight > 0.0 ? 1 : 0); }

long countStates(const SnapshotSet& states, int every) {
  long n = 0;
  for (size_t j = 0; j < states.size(); ++j) n += (static_cast<long>(states.numColumns(j)) + every - 1) / every;
  return n;
}

void checkOptions(const SystemSet& systems,
                  const SnapshotSet& states, const QuadratureOptions& o) {
  GPHR_REQUIRE(!systems.empty() && systems.size() == states.size(), InputError, "empirical quadrature: ",
               systems.size(), " systems for ", states.size(), " snapshot sets (need one per training parameter)");
  GPHR_REQUIRE(o.snapshotEvery >= 1, InputError, "eqp.snapshotEvery = ", o.snapshotEvery, " (allowed: >= 1)");
  GPHR_REQUIRE(o.energyWeight >= 0.0 && std::isfinite(o.energyWeight), InputError, "eqp.energyWeight = ",
               o.energyWeight, " (allowed: a finite number >= 0)");
  GPHR_REQUIRE(o.sketchRows >= 0, InputError, "eqp.sketchRows = ", o.sketchRows, " (allowed: >= 0)");
  GPHR_REQUIRE(o.columnFloor >= 0.0 && o.columnFloor < 1.0, InputError, "eqp.columnFloor = ", o.columnFloor,
               " (allowed: [0, 1))");
}

// CountSketch (Clarkson & Woodruff 2013): original row rho goes to one sketch row with a sign,
// both from a hash of (seed, rho) alone, so the sketch is the same on any rank count. Cost O(1)
// per entry of C, streamed; E ||S x||^2 = ||x||^2.
struct RowHash {
  int bucket;
  double sign;
};
RowHash hashRow(unsigned long long seed, long rho, int rows) {
  const unsigned long long x = hashIndex(seed, static_cast<unsigned long long>(rho));
  return {static_cast<int>((x >> 1) % static_cast<unsigned long long>(rows)), (x & 1ull) ? 1.0 : -1.0};
}

std::vector<double> localWeights(const NonlinearTerm& term) {
  auto v = term.weights()->getLocalViewHost(Tpetra::Access::ReadOnly);
  std::vector<double> out(v.extent(0));
  for (size_t i = 0; i < out.size(); ++i) out[i] = v(i, 0);
  return out;
}

double norm2(const std::vector<double>& x) {
  double s = 0.0;
  for (double a : x) s += a * a;
  return std::sqrt(s);
}

// Column gid of C, replicated: its owner copies it, the others add zeros (exact).
std::vector<double> gatherColumn(const QuadratureTraining& t, GO gid) {
  const int R = t.numRows;
  std::vector<double> mine(R, 0.0), out(R);
  const LO l = t.termMap->getLocalElement(gid);
  if (l != Teuchos::OrdinalTraits<LO>::invalid()) std::copy_n(t.columns.data() + static_cast<size_t>(l) * R, R, mine.data());
  Teuchos::reduceAll(*t.termMap->getComm(), Teuchos::REDUCE_SUM, R, mine.data(), out.data());
  return out;
}

// The active set's least-squares solve min ||C_P z - b||: R x p and dense, p = |P| small (the
// term budget), so LAPACK GELS (Householder QR) on a replicated copy; every rank computes the
// same numbers from the same data. The columns of C_P are independent by construction (a column
// enters only with a residual correlation above round-off, see selectTerm).
std::vector<double> leastSquares(const std::vector<double>& CP, int R, int p, const std::vector<double>& b) {
  GPHR_REQUIRE(p <= R, InputError, "empirical quadrature: ", p, " terms for ", R,
               " training rows (allowed: at most as many terms as rows)");
  std::vector<double> a(CP), rhs(b);
  Teuchos::LAPACK<int, double> lapack;
  int info = 0;
  double query = 0.0;
  lapack.GELS('N', R, p, 1, a.data(), R, rhs.data(), R, &query, -1, &info);
  std::vector<double> work(static_cast<size_t>(std::max(1.0, query)));
  lapack.GELS('N', R, p, 1, a.data(), R, rhs.data(), R, work.data(), static_cast<int>(work.size()), &info);
  GPHR_REQUIRE(info == 0, SolverError, "empirical quadrature: the active columns are singular (GELS info = ", info, ")");
  rhs.resize(p);
  return rhs;
}

std::vector<double> residualOf(const std::vector<double>& CP, int R, const std::vector<double>& xi,
                               const std::vector<double>& b) {
  std::vector<double> r(b);
  for (size_t j = 0; j < xi.size(); ++j)
    for (int i = 0; i < R; ++i) r[i] -= CP[j * R + i] * xi[j];
  return r;
}

// The active set of the Lawson-Hanson iteration: the terms, their columns (replicated, R x p
// column-major) and the current non-negative weights.
struct ActiveSet {
  std::vector<GO> terms;
  std::vector<double> CP, xi;
  void remove(size_t j, int R) {
    terms.erase(terms.begin() + j);
    xi.erase(xi.begin() + j);
    CP.erase(CP.begin() + j * R, CP.begin() + (j + 1) * R);
  }
};

// Lawson & Hanson (1974, Ch. 23) inner loop after a column entered with weight 0: solve the
// unconstrained problem on the active set; while some z_j <= 0, move xi towards z until the first
// weight hits zero, drop the zeros and solve again. Ends with every weight > 0.
void inner(ActiveSet& s, int R, const std::vector<double>& b) {
  for (size_t guard = 0; guard <= 3 * s.terms.size() + 3 && !s.terms.empty(); ++guard) {
    const std::vector<double> z = leastSquares(s.CP, R, static_cast<int>(s.terms.size()), b);
    double alpha = 1.0;
    size_t first = z.size();  // the weight that reaches zero first
    for (size_t j = 0; j < z.size(); ++j) {
      if (z[j] > 0.0) continue;
      const double step = s.xi[j] > 0.0 ? s.xi[j] / (s.xi[j] - z[j]) : 0.0;
      if (step < alpha) alpha = step, first = j;
    }
    if (first == z.size()) {
      s.xi = z;
      return;
    }
    for (size_t j = 0; j < z.size(); ++j) s.xi[j] += alpha * (z[j] - s.xi[j]);
    s.xi[first] = 0.0;  // exactly, not up to round-off
    for (size_t j = s.terms.size(); j-- > 0;)
      if (s.xi[j] <= 0.0) s.remove(j, R);
  }
}

// The next term: the global argmax of the correlation c_e^T r / ||c_e|| over the candidates not
// yet active. A candidate must have c_e^T r > sqrt(eps) ||c_e|| ||r||: adding it can lower ||r||^2
// by at most cos^2 ||r||^2, so below that the gain is round-off, and this keeps an (exactly or
// numerically) dependent column out of the active set. Ranking by correlation rather than Lawson
// and Hanson's raw c_e^T r does not change the optimality conditions at the end; it keeps
// columns of large norm from being chosen for their norm. Returns -1 if none qualifies.
GO selectTerm(const QuadratureTraining& t, const std::vector<char>& excluded, const std::vector<double>& r) {
  const int R = t.numRows;
  const double rn = norm2(r), cut = std::sqrt(std::numeric_limits<double>::epsilon());
  const size_t nl = t.norms.size();
  std::vector<double> score(nl, 0.0);
  std::vector<char> skip(excluded);
  for (size_t l = 0; l < nl; ++l) {
    if (skip[l]) continue;
    const double* c = t.columns.data() + l * R;
    double w = 0.0;
    for (int i = 0; i < R; ++i) w += c[i] * r[i];
    score[l] = w / t.norms[l];
    skip[l] = !(score[l] > cut * rn);
  }
  const auto [gid, val] = globalArgmaxAbs(*t.termMap, score, skip);
  return val > 0.0 ? gid : -1;
}

std::vector<char> nonCandidates(const QuadratureTraining& t) {
  std::vector<char> ex(t.norms.size());
  for (size_t l = 0; l < ex.size(); ++l) ex[l] = !(t.norms[l] > t.columnFloor * t.maxNorm) || t.norms[l] == 0.0;
  return ex;
}

void markExcluded(const QuadratureTraining& t, std::vector<char>& ex, GO gid) {
  const LO l = t.termMap->getLocalElement(gid);
  if (l != Teuchos::OrdinalTraits<LO>::invalid()) ex[l] = 1;
}

double relativeResidual(const ActiveSet& s, const QuadratureTraining& t) {
  return norm2(residualOf(s.CP, t.numRows, s.xi, t.target)) / norm2(t.target);
}

void requireTarget(const QuadratureTraining& t) {
  GPHR_REQUIRE(t.numRows > 0 && norm2(t.target) > 0.0, InputError, "empirical quadrature: the target (the reduced "
               "nonlinear gradient over ", t.snapshots, " training states) is zero: nothing to fit");
}

}  // namespace

QuadratureTraining buildQuadratureTraining(const SystemSet& systems,
                                           const SnapshotSet& states, const MultiVector& A,
                                           const QuadratureOptions& o) {
  checkOptions(systems, states, o);
  const NonlinearTerm& term = systems[0]->nonlinearTerm();
  QuadratureTraining t;
  t.termMap = term.rowMap();
  t.columnFloor = o.columnFloor;
  t.v = localWeights(term);
  const int r = static_cast<int>(A.getNumVectors()), rps = rowsPerState(r, o);
  const size_t nl = t.v.size();
  const long exact = countStates(states, o.snapshotEvery) * rps;
  GPHR_REQUIRE(exact > 0, InputError, "empirical quadrature: no training states (", states.size(),
               " training runs with no stored state)");
  t.sketched = o.sketchRows > 0;
  t.numRows = t.sketched ? o.sketchRows : static_cast<int>(exact);
  GPHR_REQUIRE(static_cast<double>(nl) * t.numRows <= o.maxNumbersPerRank, InputError, "empirical quadrature: ",
               nl, " terms x ", t.numRows, " training rows on one rank exceed ", o.maxNumbersPerRank,
               " numbers; allowed: fewer rows (eqp.sketchRows > 0, or a larger eqp.snapshotEvery) or more ranks");
  t.columns.assign(nl * t.numRows, 0.0);
  std::vector<Scalar> jac(nl * r), values(nl);
  const int R = t.numRows;
  // Where each of a state's rows goes (its own row, or its sketch row and sign): one hash per row
  // and state, shared by all the terms.
  std::vector<long> dest(rps);
  std::vector<double> sign(rps, 1.0);
  auto destinations = [&](long s) {
    for (int a = 0; a < rps; ++a) {
      const long rho = s * rps + a;
      if (!t.sketched) {
        dest[a] = rho;
        continue;
      }
      const RowHash h = hashRow(o.seed, rho, R);
      dest[a] = h.bucket, sign[a] = h.sign;
    }
  };
  t.snapshots = forEachJacobianSnapshot(systems, states, A, o.snapshotEvery, jac,
                                        [&](const std::vector<Scalar>& J, long s, ReducedRowKernel& kernel) {
    destinations(s);
    if (o.energyWeight > 0.0) kernel.rowValues(values.data());
    for (size_t l = 0; l < nl; ++l) {
      double* c = t.columns.data() + l * R;
      for (int a = 0; a < r; ++a) c[dest[a]] += sign[a] * J[l * r + a];
      if (o.energyWeight > 0.0) c[dest[r]] += sign[r] * o.energyWeight * values[l];
    }
  });
  std::vector<double> b(R, 0.0);
  t.norms.resize(nl);
  double maxLocal = 0.0;
  for (size_t l = 0; l < nl; ++l) {
    const double* c = t.columns.data() + l * R;
    double s = 0.0;
    for (int i = 0; i < R; ++i) s += c[i] * c[i], b[i] += t.v[l] * c[i];
    t.norms[l] = std::sqrt(s);
    maxLocal = std::max(maxLocal, t.norms[l]);
  }
  t.target.resize(R);
  const auto& comm = *t.termMap->getComm();
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, R, b.data(), t.target.data());
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, maxLocal, Teuchos::outArg(t.maxNorm));
  return t;
}

namespace {
QuadratureFit snapshotOf(const ActiveSet& s, const QuadratureTraining& t, const std::string& stop, int selections,
                         double seconds) {
  GPHR_REQUIRE(!s.terms.empty(), InputError, "empirical quadrature: no candidate term correlates positively with the "
               "target (", selections, " selections; candidates are columns above eqp.columnFloor = ", t.columnFloor,
               " x the largest)");
  QuadratureFit fit;
  fit.terms = s.terms, fit.weights = s.xi, fit.stop = stop, fit.iterations = selections, fit.seconds = seconds;
  fit.residual = relativeResidual(s, t);
  return fit;
}
}  // namespace

std::vector<QuadratureFit> nnlsQuadraturePath(const QuadratureTraining& t, const std::vector<int>& budgets,
                                              double tolerance) {
  GPHR_REQUIRE(!budgets.empty(), InputError, "empirical quadrature: no term budget given");
  for (int b : budgets) GPHR_REQUIRE(b >= 1, InputError, "empirical quadrature: term budget ", b, " (allowed: >= 1)");
  GPHR_REQUIRE(tolerance >= 0.0 && tolerance < 1.0, InputError, "eqp.tolerance = ", tolerance,
               " (allowed: [0, 1))");
  requireTarget(t);
  Teuchos::Time clock("eqp path");
  clock.start();
  const int R = t.numRows;
  std::vector<char> excluded = nonCandidates(t);
  ActiveSet s;
  std::vector<QuadratureFit> fits(budgets.size());
  std::vector<char> done(budgets.size(), 0);
  size_t open = budgets.size();
  // Records the current active set for every budget still open that `reached` says is done.
  auto record = [&](const std::string& stop, int selections, auto&& reached) {
    for (size_t i = 0; i < budgets.size(); ++i)
      if (!done[i] && reached(budgets[i])) fits[i] = snapshotOf(s, t, stop, selections, clock.totalElapsedTime(true)), done[i] = 1, --open;
  };
  std::vector<double> r = t.target;
  const double bn = norm2(t.target);
  // Below ~10 eps ||b|| the residual is the least-squares solve's round-off: a column correlating
  // with it would enter for noise, so that is where a zero tolerance stops.
  const double stopAt = std::max(tolerance, 10.0 * std::numeric_limits<double>::epsilon());
  int selections = 0;
  // Each selection adds one term; the inner loop may drop some again. 4 budget + 16 selections
  // bound a budget's run (Lawson-Hanson terminates in exact arithmetic; round-off could cycle).
  for (int it = 0; open > 0; ++it) {
    record("iterations", selections, [&](int b) { return it >= 4 * b + 16; });
    if (open == 0) break;
    if (norm2(r) <= stopAt * bn) {
      record("tolerance", selections, [](int) { return true; });
      break;
    }
    std::vector<char> skip(excluded);
    for (GO g : s.terms) markExcluded(t, skip, g);  // the active columns
    const GO gid = selectTerm(t, skip, r);
    if (gid < 0) {
      record("optimal", selections, [](int) { return true; });
      break;
    }
    ++selections;
    const std::vector<double> c = gatherColumn(t, gid);
    s.terms.push_back(gid), s.xi.push_back(0.0), s.CP.insert(s.CP.end(), c.begin(), c.end());
    inner(s, R, t.target);
    // A column the inner loop dropped at once (its weight could not become positive: round-off)
    // is never selected again; columns dropped later return to the candidates, as in Lawson-Hanson.
    if (std::find(s.terms.begin(), s.terms.end(), gid) == s.terms.end()) markExcluded(t, excluded, gid);
    r = residualOf(s.CP, R, s.xi, t.target);
    record("budget", selections, [&](int b) { return static_cast<int>(s.terms.size()) >= b; });
  }
  return fits;
}

QuadratureFit nnlsQuadrature(const QuadratureTraining& t, int budget, double tolerance) {
  return nnlsQuadraturePath(t, {budget}, tolerance).front();
}

QuadratureFit refitQuadrature(const QuadratureTraining& t, const std::vector<GO>& terms) {
  requireTarget(t);
  Teuchos::Time clock("eqp refit");
  clock.start();
  GPHR_REQUIRE(!terms.empty(), InputError, "empirical quadrature refit: no terms given");
  ActiveSet s;
  for (GO gid : terms) {
    GPHR_REQUIRE(gid >= t.termMap->getMinAllGlobalIndex() && gid <= t.termMap->getMaxAllGlobalIndex(), InputError,
                 "empirical quadrature refit: term ", gid, " is not a row of G (allowed: ",
                 t.termMap->getMinAllGlobalIndex(), "..", t.termMap->getMaxAllGlobalIndex(), ")");
    const std::vector<double> c = gatherColumn(t, gid);
    s.terms.push_back(gid), s.CP.insert(s.CP.end(), c.begin(), c.end());
  }
  s.xi = leastSquares(s.CP, t.numRows, static_cast<int>(terms.size()), t.target);
  QuadratureFit fit;
  fit.terms = s.terms, fit.weights = s.xi, fit.stop = "refit";
  fit.residual = relativeResidual(s, t);
  fit.seconds = clock.stop();
  return fit;
}

double exactRowsResidual(const SystemSet& systems,
                         const SnapshotSet& states, const MultiVector& A,
                         const QuadratureOptions& o, const QuadratureFit& fit) {
  checkOptions(systems, states, o);
  const NonlinearTerm& term = systems[0]->nonlinearTerm();
  const Map& map = *term.rowMap();
  const std::vector<double> v = localWeights(term);
  const size_t nl = v.size();
  std::vector<double> coef(nl);  // xi_l - v_l: the residual C (xi - v) one state at a time
  for (size_t l = 0; l < nl; ++l) coef[l] = -v[l];
  for (size_t j = 0; j < fit.terms.size(); ++j) {
    const LO l = map.getLocalElement(fit.terms[j]);
    if (l != Teuchos::OrdinalTraits<LO>::invalid()) coef[l] += fit.weights[j];
  }
  const int r = static_cast<int>(A.getNumVectors()), rps = rowsPerState(r, o);
  std::vector<Scalar> jac(nl * r), values(nl);
  std::vector<double> part(2 * rps), sum(2 * rps);  // residual rows, then target rows
  double res2 = 0.0, tgt2 = 0.0;
  forEachJacobianSnapshot(systems, states, A, o.snapshotEvery, jac,
                          [&](const std::vector<Scalar>& J, long, ReducedRowKernel& kernel) {
    std::fill(part.begin(), part.end(), 0.0);
    if (o.energyWeight > 0.0) kernel.rowValues(values.data());
    for (size_t l = 0; l < nl; ++l) {
      for (int a = 0; a < r; ++a) part[a] += coef[l] * J[l * r + a], part[rps + a] += v[l] * J[l * r + a];
      if (o.energyWeight > 0.0)
        part[r] += coef[l] * o.energyWeight * values[l], part[rps + r] += v[l] * o.energyWeight * values[l];
    }
    Teuchos::reduceAll(*map.getComm(), Teuchos::REDUCE_SUM, 2 * rps, part.data(), sum.data());
    for (int a = 0; a < rps; ++a) res2 += sum[a] * sum[a], tgt2 += sum[rps + a] * sum[rps + a];
  });
  return tgt2 > 0.0 ? std::sqrt(res2 / tgt2) : 0.0;
}

RCP<GpDeimModel> buildQuadratureModel(const HamiltonianSystem& system, const MultiVector& A, const QuadratureFit& fit,
                                      const ReducedLinearPart& linear) {
  return rcp(new GpDeimModel(system.nonlinearTermPtr(), buildSampleMesh(system, A, fit.terms, fit.weights, linear)));
}

Teuchos::ParameterList quadratureValidParameters() {
  Teuchos::ParameterList eq("eqp");
  setDoubleParameter(eq, "tolerance", 0.0, 0.0, 0.999999,
                     "gp-eqp: stop adding terms once the relative fit residual ||C xi - b|| / ||b|| is at most this; "
                     "0: pipeline.m terms (or fewer, when no further term improves the fit)");
  setIntParameter(eq, "snapshotEvery", 1, 1, 1000000,
                  "gp-eqp, gp-eqp-refit: fit the reduced gradient at every N-th stored training state");
  setIntParameter(eq, "sketchRows", 0, 0, 100000000,
                  "rows of the fit: 0, the exact rows (training states x 2k, held as terms x rows per rank: refused "
                  "above 2.5e8 numbers); > 0, a CountSketch of them to this many rows (the fit's residual on the "
                  "exact rows is reported beside, as eqp_fit_residual_exact_rows)");
  setDoubleParameter(eq, "energyWeight", 0.0, 0.0, 1e12,
                     "> 0: one more row per training state fitting the energy G_e - G_e(y0), scaled by this; 0: the "
                     "gradient rows only");
  setDoubleParameter(eq, "columnFloor", 1e-3, 0.0, 0.999999,
                     "terms whose column norm is at most this times the largest are not candidates (a term that "
                     "never moves in training would get an unbounded weight; doc/eqp.md measures 1e-6 against 1e-3)");
  setIntParameter(eq, "seed", 20261124, 0, 2147483647, "sketchRows > 0: the sketch's hash seed");
  return eq;
}

std::string quadratureCacheKey(const QuadratureOptions& o, double tolerance) {
  return CacheKey("term-weight fits", 1)
      .add("tolerance", tolerance)
      .add("snapshotEvery", o.snapshotEvery)
      .add("energyWeight", o.energyWeight)
      .add("sketchRows", o.sketchRows)
      .add("columnFloor", o.columnFloor)
      .add("seed", o.seed)
      .str();
}

QuadratureOptions quadratureOptionsFrom(const Teuchos::ParameterList& eq) {
  QuadratureOptions o;
  o.snapshotEvery = eq.get<int>("snapshotEvery");
  o.energyWeight = eq.get<double>("energyWeight");
  o.sketchRows = eq.get<int>("sketchRows");
  o.columnFloor = eq.get<double>("columnFloor");
  o.seed = static_cast<unsigned long long>(eq.get<int>("seed"));
  return o;
}

}  // namespace gphr
