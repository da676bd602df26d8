#include "gphr/hyper/GpAdeimModel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include <Teuchos_BLAS.hpp>
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_OrdinalTraits.hpp>
#include <Teuchos_Time.hpp>
#include <Teuchos_TimeMonitor.hpp>

#include "gphr/core/Error.hpp"
#include "gphr/core/ParameterValidation.hpp"
#include "gphr/core/ReplicatedGather.hpp"
#include "gphr/hyper/AdeimSampling.hpp"
#include "gphr/hyper/DeimBasis.hpp"
#include "gphr/reduction/Deim.hpp"
#include "gphr/reduction/PivotedCholesky.hpp"
#include "gphr/reduction/SymmetricEigen.hpp"
#include "gphr/timeint/FullModelIntegrator.hpp"
#include "gphr/timeint/ObservedTimeLoop.hpp"

namespace gphr {

Teuchos::ParameterList adeimValidParameters() {
  Teuchos::ParameterList pl("adeim");
  setIntParameter(pl, "initialWindow", 5, 1, 1000000, "delta0: full-model steps for (U_0, P_0); first update after them");
  setIntParameter(pl, "updateEvery", 5, 1, 1000000, "delta: steps between DEIM basis updates");
  setIntParameter(pl, "window", 1, 1, 1000000, "w: reduced states in the snapshot window F_j (w < delta0)");
  setIntParameter(pl, "resampleEvery", 5, 1, 1000000, "gamma: steps between sampling-row updates (a multiple of delta)");
  setIntParameter(pl, "updateRank", 0, 0, 1000000, "r: fixed update rank; 0 = numerical rank of S^T R C^T by rankTol");
  setDoubleParameter(pl, "rankTol", 1e-12, 0.0, 1.0,
                     "tau_r: sigma_i(S^T R C^T) > rankTol sigma_1 (relative; 0 = every non-zero direction, r-bar)");
  setDoubleParameter(pl, "coefficientTol", 1e-10, 0.0, 1.0,
                     "directions of C_j with |R_ll| <= coefficientTol |R_11| in the column-pivoted QR of C_j^T are "
                     "dropped (C C^T would be numerically singular below 1e-8 but is never formed: the QR resolves "
                     "down to ~wbar eps; a kept direction moves U by ~1 / |R_ll|)");
  setIntParameter(pl, "numSamples", 0, 0, 100000000, "m_s: sampling rows (>= m; at most the d - m rows outside P, fewer if d - m is smaller); 0 = chosen by sampleTol");
  setDoubleParameter(pl, "sampleTol", 1e-3, 0.0, 1.0,
                     "tau_s: rows whose score exceeds sampleTol x the largest score (relative: the scale of F does not matter)");
  setIntParameter(pl, "maxSamples", 0, 0, 100000000, "cap on m_s chosen by sampleTol; 0 = 4 m");
  setChoiceParameter(pl, "sampling", "projected", Teuchos::tuple<std::string>("projected", "residual", "random"),
                     "sampling rule: rows of R_j C_bar_j (alg:indices_adapt), of R_j (Peherstorfer 2020), or random");
  setChoiceParameter(pl, "indices", "deim", Teuchos::tuple<std::string>("deim", "qdeim", "partial"),
                     "interpolation rows P_{j+1} from U_{j+1}: greedy DEIM, QDEIM, or the partial update of "
                     "Peherstorfer & Willcox 2015 Sec. 4.1 (only the rows of the most rotated columns re-chosen)");
  setIntParameter(pl, "pointUpdates", 1, 1, 1000000,
                  "indices = partial: interpolation rows re-chosen per update, those of the most rotated columns (<= m)");
  setChoiceParameter(pl, "initialBasis", "fom", Teuchos::tuple<std::string>("fom", "training"),
                     "(U_0, P_0) from the first initialWindow full-model steps at the test parameter, or the training DEIM basis");
  pl.set("orthonormalize", true,
         "replace U_{j+1} by an orthonormal basis of its span before choosing P_{j+1} (columns in column-pivoted QR "
         "order, from the pivoted Cholesky factor of the Gram matrix; "
         "with indices = partial the nearest one, U G^{-1/2}); the DEIM projection depends only on span(U) and P");
  pl.set("monitorResidual", true, "record ||U_{j+1} C_j - F_j||_F over all d rows at every update (O(d) each)");
  setIntParameter(pl, "seed", 20240601, 0, 2147483647, "seed of the random sampling rule");
  setDoubleParameter(pl, "updateTol", 0.0, 0.0, 1e6,
                     "an update runs only when ||S^T R_j||_F / ||S^T F_j||_F at the current sampling rows exceeds "
                     "updateTol (0 = every updateEvery steps, the paper's rule; the first update always runs)");
  return pl;
}

AdeimOptions adeimOptionsFrom(Teuchos::ParameterList pl) {
  validateParameters(pl, adeimValidParameters(), "adeim");
  AdeimOptions o;
  o.initialWindow = pl.get<int>("initialWindow");
  o.updateEvery = pl.get<int>("updateEvery");
  o.window = pl.get<int>("window");
  o.resampleEvery = pl.get<int>("resampleEvery");
  o.update.rank = pl.get<int>("updateRank");
  o.update.rankTol = pl.get<double>("rankTol");
  o.update.coefficientTol = pl.get<double>("coefficientTol");
  o.numSamples = pl.get<int>("numSamples");
  o.sampleTol = pl.get<double>("sampleTol");
  o.maxSamples = pl.get<int>("maxSamples");
  o.sampling = pl.get<std::string>("sampling");
  o.indices = pl.get<std::string>("indices");
  o.pointUpdates = pl.get<int>("pointUpdates");
  o.initialBasis = pl.get<std::string>("initialBasis");
  o.monitorResidual = pl.get<bool>("monitorResidual");
  o.orthonormalize = pl.get<bool>("orthonormalize");
  o.seed = static_cast<unsigned long long>(pl.get<int>("seed"));
  o.updateTol = pl.get<double>("updateTol");
  GPHR_REQUIRE(o.window < o.initialWindow, InputError, "adeim.window = ", o.window, " must be smaller than adeim.initialWindow = ",
               o.initialWindow, " (the window of the first update lies in the first delta0 steps)");
  GPHR_REQUIRE(o.resampleEvery % o.updateEvery == 0, InputError, "adeim.resampleEvery = ", o.resampleEvery,
               " must be a multiple of adeim.updateEvery = ", o.updateEvery, " (sampling rows change at updates)");
  GPHR_REQUIRE(o.sampling != "random" || o.numSamples > 0, InputError,
               "adeim.sampling = random needs adeim.numSamples > 0 (sampleTol ranks rows by their residual)");
  return o;
}

AdeimOptions adeimOptionsFor(AdeimOptions o, int m) {
  if (o.maxSamples == 0) o.maxSamples = 4 * m;
  GPHR_REQUIRE(o.numSamples == 0 || o.numSamples >= m, InputError, "adeim.numSamples = ", o.numSamples,
               " must be at least m = ", m, " (or 0 to choose it by sampleTol)");
  GPHR_REQUIRE(o.maxSamples >= m, InputError, "adeim.maxSamples = ", o.maxSamples, " must be at least m = ", m);
  GPHR_REQUIRE(o.update.rank <= m, InputError, "adeim.updateRank = ", o.update.rank, " exceeds m = ", m);
  GPHR_REQUIRE(o.pointUpdates <= m, InputError, "adeim.pointUpdates = ", o.pointUpdates, " exceeds m = ", m);
  return o;
}

AdeimOptions adeimOptionsFrom(Teuchos::ParameterList pl, int m) { return adeimOptionsFor(adeimOptionsFrom(pl), m); }

Teuchos::ParameterList adeimParameters(const AdeimOptions& o) {
  Teuchos::ParameterList pl("adeim");
  pl.set("initialWindow", o.initialWindow).set("updateEvery", o.updateEvery).set("window", o.window);
  pl.set("resampleEvery", o.resampleEvery).set("updateRank", o.update.rank).set("rankTol", o.update.rankTol);
  pl.set("coefficientTol", o.update.coefficientTol).set("numSamples", o.numSamples).set("sampleTol", o.sampleTol);
  pl.set("maxSamples", o.maxSamples).set("sampling", o.sampling).set("indices", o.indices);
  pl.set("pointUpdates", o.pointUpdates).set("initialBasis", o.initialBasis).set("orthonormalize", o.orthonormalize);
  pl.set("monitorResidual", o.monitorResidual).set("seed", static_cast<int>(o.seed)).set("updateTol", o.updateTol);
  return pl;
}

namespace {
// Timers of the adaptation's phases (printed in the run's timer table).
Teuchos::Time& phase(const char* name) {
  return *Teuchos::TimeMonitor::getNewCounter(std::string("gphr: gp-adeim ") + name);
}

DenseMatrix toDense(const std::vector<double>& rowMajor, int rows, int cols) {
  DenseMatrix M(rows, cols, false);  // every entry written below
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) M(i, j) = rowMajor[static_cast<size_t>(i) * cols + j];
  return M;
}

// Interpolation rows of U's first m columns (greedy DEIM or QDEIM), under the phase timer. Collective.
std::vector<GO> timedIndices(const MultiVector& U, int m, const std::string& method) {
  Teuchos::TimeMonitor tm(phase("indices: selection"));
  return selectDeimIndices(U, m, method);
}

// The GP-DEIM row kernel of (U, P): the weights and the sample mesh of P (`known`: the previous
// sample, whose rows need no new gather). `info`: the weights' cond(P^T U) and P^T U. Collective.
template <class Basis>
RCP<ReducedRowKernel> interpolationKernel(const HamiltonianSystem& system, const Basis& A, const MultiVector& U,
                                          const std::vector<GO>& P, const RowSample& known = RowSample(),
                                          DeimWeights* info = nullptr) {
  DeimWeights w;
  {
    Teuchos::TimeMonitor tm(phase("indices: weights"));
    w = computeDeimWeights(U, P, *system.nonlinearTerm().weights(), true);
  }
  Teuchos::TimeMonitor tm(phase("indices: sample mesh of P"));
  auto kernel = rcp(
      new ReducedRowKernel(system.nonlinearTermPtr(), gatherRowSample(system, A, P, w.weights, known), Teuchos::null));
  if (info) *info = std::move(w);
  return kernel;
}

RCP<MultiVector> leadingColumns(const MultiVector& U, int m) {
  GPHR_REQUIRE(m >= 1 && static_cast<size_t>(m) <= U.getNumVectors(), InputError, "GP-ADEIM: m = ", m,
               " but the initial DEIM basis has ", U.getNumVectors(), " columns");
  return rcp(new MultiVector(*U.subCopy(Teuchos::Range1D(0, m - 1))));
}
}  // namespace

GpAdeimModel::GpAdeimModel(RCP<const HamiltonianSystem> system, RCP<const MultiVector> A, const MultiVector& U0, int m,
                           ReducedLinearPart linear, AdeimOptions options)
    : GpAdeimModel(std::move(system), std::move(A), leadingColumns(U0, m), std::move(linear), std::move(options)) {}

// U: the initial basis's first m columns, one copy serving the initial kernel and U_.
GpAdeimModel::GpAdeimModel(RCP<const HamiltonianSystem> system, RCP<const MultiVector> A, RCP<MultiVector> U,
                           ReducedLinearPart linear, AdeimOptions options)
    : ReducedHamiltonian(std::move(linear),
                         interpolationKernel(*system, *A, *U,
                                             timedIndices(*U, static_cast<int>(U->getNumVectors()),
                                                          options.indices == "partial" ? "deim" : options.indices))),
      system_(system),
      A_(A),
      U_(U),
      m_(static_cast<int>(U->getNumVectors())),
      opt_(std::move(options)) {
  // The resampling scores and the update read U's and F_j's own rows by the same local index.
  GPHR_REQUIRE(U_->getMap()->isSameAs(*system_->nonlinearTerm().rowMap()), InputError,
               "GP-ADEIM: the DEIM basis is not distributed like the rows of the nonlinear term G");
  P_ = rows().sample().rows;
  Arows_ = rcp(new LocalRows(*A_));
  owned_ = rcp(new ReducedRowKernel(system_->nonlinearTermPtr(), ownedRowSample(*system_, *A_), Teuchos::null));
}

bool GpAdeimModel::isUpdateStep(long step) const {
  return step >= opt_.initialWindow && (step - opt_.initialWindow) % opt_.updateEvery == 0;
}

// Reduced-Jacobian rows J_G(y0 + A z_s) A of the kernel's rows for the window states, side by
// side: row-major rows x (2k w).
void GpAdeimModel::windowSnapshots(ReducedRowKernel& kernel, std::vector<double>& F) {
  const int r = kernel.reducedDim(), rows = kernel.numRows(), cols = r * static_cast<int>(window_.size());
  F.resize(static_cast<size_t>(rows) * cols);
  int s = 0;
  for (const DenseVector& z : window_) {  // state s fills columns s r .. (s + 1) r - 1 of every row
    kernel.evaluate(z, true, false);
    kernel.reducedJacobian(F.data() + static_cast<size_t>(s) * r, static_cast<size_t>(cols));
    ++s;
  }
}

bool GpAdeimModel::afterStep(long step, const DenseVector& z) {
  window_.push_back(z);
  if (static_cast<int>(window_.size()) > opt_.window) window_.pop_front();
  if (!isUpdateStep(step)) return false;
  Teuchos::Time timer("adeim");
  timer.start();
  AdeimUpdateRecord rec;
  rec.step = step;
  rec.hrBefore = hamiltonian(z);
  const int wbar = rows().reducedDim() * static_cast<int>(window_.size());
  std::vector<double> F;
  DenseMatrix C;
  {
    Teuchos::TimeMonitor tm(phase("window at P"));
    windowSnapshots(rows(), F);
    forgetEvaluation();
    if (PtU_.numRows() != m_) PtU_ = toDense(gatherRows(*U_, P_), m_, m_);  // the first update only
    C = deimCoefficients(PtU_, toDense(F, m_, wbar));
  }
  if (opt_.updateTol > 0.0 && !S_.empty()) {
    Teuchos::TimeMonitor tm(phase("update indicator"));
    rec.indicator = updateIndicator(C, wbar);
    if (rec.indicator <= opt_.updateTol) {  // U, P and S stay: the model goes on unchanged
      rec.skipped = true;
      rec.numSamples = static_cast<int>(S_.size());
      rec.hrAfter = rec.hrBefore;
      rec.seconds = timer.stop();
      records_.push_back(rec);
      return false;
    }
  }
  CoefficientFactor cf;
  {
    Teuchos::TimeMonitor tm(phase("coefficient factor"));
    cf = factorCoefficients(std::move(C), opt_.update.coefficientTol);
  }
  ownedFValid_ = false;
  const long updateNo = (step - opt_.initialWindow) / opt_.updateEvery;
  if ((step - opt_.initialWindow) % opt_.resampleEvery == 0 || S_.empty()) {
    Teuchos::TimeMonitor tm(phase("resampling"));
    resample(cf, updateNo);
    rec.resampled = true;
  }
  if (S_.empty()) {  // m = d: no row outside P, and the DEIM projection is the identity
    rec.hrAfter = rec.hrBefore;
    rec.seconds = timer.stop();
    records_.push_back(rec);
    return false;
  }
  const AdeimUpdate up = updateSampledRows(cf, wbar, F);
  rec.rank = up.rank;
  rec.coefficientRank = up.coefficientRank;
  rec.numSamples = static_cast<int>(S_.size());
  rec.sampledBefore = up.residualBefore;
  rec.sampledAfter = up.residualAfter;
  if (opt_.monitorResidual) {
    Teuchos::TimeMonitor tm(phase("residual monitor"));
    std::tie(rec.fullResidual, rec.windowNorm) = fullResidual(cf);
  }
  if (up.rank > 0) {
    const std::vector<double> rotation = opt_.indices == "partial" ? columnRotations(up) : std::vector<double>();
    if (opt_.orthonormalize) {
      Teuchos::TimeMonitor tm(phase("orthonormalization"));
      orthonormalizeBasis();
    }
    rec.condPtU = moveInterpolationRows(rotation);
  }
  rec.hrAfter = hamiltonian(z);
  rec.seconds = timer.stop();
  records_.push_back(rec);
  return up.rank > 0;
}

namespace {
// The rows `which` (positions in s.rows) of a row sample with their stencils, weights, rows of A
// and reference values: a sample of a subset, copied without communication.
RowSample subSample(const RowSample& s, const std::vector<LO>& which) {
  RowSample out;
  out.shifted = s.shifted;
  out.reducedDim = s.reducedDim;
  const size_t r = static_cast<size_t>(s.reducedDim);
  for (LO i : which) {
    out.rows.push_back(s.rows[i]);
    out.weights.push_back(s.weights[i]);
    for (size_t e = s.stencil.offsets[i]; e < s.stencil.offsets[i + 1]; ++e) {
      out.stencil.gids.push_back(s.stencil.gids[e]);
      out.basisRows.insert(out.basisRows.end(), s.basisRows.begin() + e * r, s.basisRows.begin() + (e + 1) * r);
      out.reference.push_back(s.reference[e]);
    }
    out.stencil.offsets.push_back(out.stencil.gids.size());
  }
  return out;
}
}  // namespace

// The indicator of adeim.updateTol: the DEIM fit's relative residual at the current sampling rows,
// ||S^T (U C - F)||_F / ||S^T F||_F, each rank on its own rows of S (ownSampledKernel: S^T F_j at
// its 2k w columns; S^T U C an own-rows x m x wbar product); one sum-reduction of the two squares.
// 0 when S^T F and the residual vanish, +inf when only S^T F does. Collective.
double GpAdeimModel::updateIndicator(const DenseMatrix& C, int wbar) {
  std::vector<double> Fs;
  windowSnapshots(ownSampledKernel(), Fs);  // own rows of S, row-major own x wbar
  const std::vector<LO>& local = ownSampledRows_;
  const int own = static_cast<int>(local.size());
  DenseMatrix StU(own, m_, false), X(own, wbar, false);  // every entry written below
  {
    auto u = U_->getLocalViewHost(Tpetra::Access::ReadOnly);
    for (int j = 0; j < m_; ++j)
      for (int i = 0; i < own; ++i) StU(i, j) = u(local[i], j);
  }
  double sums[2] = {0.0, 0.0}, global[2] = {0.0, 0.0};
  for (int i = 0; i < own; ++i)
    for (int c = 0; c < wbar; ++c) {
      const double f = Fs[static_cast<size_t>(i) * wbar + c];
      X(i, c) = f;
      sums[1] += f * f;
    }
  if (own > 0) X.multiply(Teuchos::NO_TRANS, Teuchos::NO_TRANS, 1.0, StU, C, -1.0);  // S^T U C - S^T F
  for (int c = 0; c < wbar; ++c)
    for (int i = 0; i < own; ++i) sums[0] += X(i, c) * X(i, c);
  Teuchos::reduceAll(*U_->getMap()->getComm(), Teuchos::REDUCE_SUM, 2, sums, global);
  if (global[1] > 0.0) return std::sqrt(global[0] / global[1]);
  return global[0] > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
}

// alg:basis_adapt lines 4-9 at the sampling rows, each rank on its own rows of S: S^T F_j,
// S^T U_j, the rank-r update (computeAdeimUpdate assembles the small m_s x r_C product it
// factors) and S^T U_{j+1} written back into U. Nothing of S is gathered. Collective.
AdeimUpdate GpAdeimModel::updateSampledRows(const CoefficientFactor& cf, int wbar, std::vector<double>& F) {
  Teuchos::TimeMonitor tm(phase("rank-r update"));
  const Map& map = *U_->getMap();
  SampledRowShare share;
  share.comm = map.getComm();
  share.numRows = static_cast<int>(S_.size());
  std::vector<LO> local;  // U's local row of each own sampling row
  for (int i = 0; i < share.numRows; ++i) {
    const LO l = map.getLocalElement(S_[i]);
    if (l == Teuchos::OrdinalTraits<LO>::invalid()) continue;
    share.positions.push_back(i);
    local.push_back(l);
  }
  const int own = static_cast<int>(local.size());
  DenseMatrix StF(own, wbar), StU(own, m_);
  if (ownedFValid_) {  // resampled at this update: F_j on the own rows is at hand (U's local order)
    for (int i = 0; i < own; ++i)
      for (int c = 0; c < wbar; ++c) StF(i, c) = ownedF_[static_cast<size_t>(local[i]) * wbar + c];
  } else {  // this rank's rows of S (in S's order)
    windowSnapshots(ownSampledKernel(), F);
    for (int i = 0; i < own; ++i)
      for (int c = 0; c < wbar; ++c) StF(i, c) = F[static_cast<size_t>(i) * wbar + c];
  }
  {
    auto u = U_->getLocalViewHost(Tpetra::Access::ReadOnly);
    for (int c = 0; c < m_; ++c)
      for (int i = 0; i < own; ++i) StU(i, c) = u(local[i], c);
  }
  AdeimUpdate up;
  {
    Teuchos::TimeMonitor dense(phase("rank-r update: dense algebra"));
    up = computeAdeimUpdate(cf, StU, StF, opt_.update, share);
  }
  if (up.rank > 0) {
    applyAdeimUpdate(up, share, StU);
    auto u = U_->getLocalViewHost(Tpetra::Access::ReadWrite);
    for (int c = 0; c < m_; ++c)
      for (int i = 0; i < own; ++i) u(local[i], c) = StU(i, c);
  }
  return up;
}

// Per own row, the residual norms of the DEIM fit (projected on V, or plain), reading U's local
// column-major view in place.
namespace {
std::vector<double> ownRowScores(const MultiVector& U, const std::vector<double>& F, int rows,
                                 const CoefficientFactor& cf, bool projected) {
  auto u = U.getLocalViewHost(Tpetra::Access::ReadOnly);
  const int ld = std::max<int>(1, static_cast<int>(u.stride(1)));
  return residualRowNorms(u.data(), ld, F, rows, cf, projected);
}
}  // namespace

void GpAdeimModel::resample(const CoefficientFactor& cf, long updateNo) {
  const Map& rowMap = *system_->nonlinearTerm().rowMap();
  if (opt_.sampling == "random") {
    S_ = randomRows(rowMap, P_, opt_.numSamples, opt_.seed, updateNo);
  } else {
    if (!ownedFValid_) {
      Teuchos::TimeMonitor tm(phase("resampling: F_j on own rows"));
      windowSnapshots(*owned_, ownedF_);
      ownedFValid_ = true;
    }
    std::vector<double> scores;
    {
      Teuchos::TimeMonitor tm(phase("resampling: row scores"));
      scores = ownRowScores(*U_, ownedF_, owned_->numRows(), cf, opt_.sampling == "projected");
    }
    SampleCount count;
    count.fixed = opt_.numSamples;
    count.relTol = opt_.sampleTol;
    count.atLeast = m_;
    count.atMost = opt_.maxSamples;
    Teuchos::TimeMonitor tm(phase("resampling: select"));
    S_ = largestScoreRows(rowMap, scores, P_, count);
  }
  ownSampled_ = Teuchos::null;
}

// This rank's rows of S as a row kernel, copied from the own rows' kernel (their stencils and rows
// of A are at hand) when S has changed: S^T F_j for an update without a resampling (gamma >
// delta; with gamma = delta the update reads F_j on the own rows) and for the update indicator.
// No communication: the replicated sample mesh of S it replaces gathered rows of A, 1.7 ms per
// build at the paper's NLS size. The same rows of F_j, to the rounding of the lift's GEMV (whose
// kernel may sum a row differently by its place in the batch), as F_j on the own rows already is.
ReducedRowKernel& GpAdeimModel::ownSampledKernel() {
  if (ownSampled_.is_null()) {
    Teuchos::TimeMonitor tm(phase("sample mesh of S"));
    const Map& map = *U_->getMap();
    ownSampledRows_.clear();
    for (GO g : S_) {
      const LO l = map.getLocalElement(g);
      if (l != Teuchos::OrdinalTraits<LO>::invalid()) ownSampledRows_.push_back(l);
    }
    ownSampled_ = rcp(new ReducedRowKernel(system_->nonlinearTermPtr(), subSample(owned_->sample(), ownSampledRows_),
                                           Teuchos::null));
  }
  return *ownSampled_;
}

std::pair<double, double> GpAdeimModel::fullResidual(const CoefficientFactor& cf) {
  if (!ownedFValid_) {
    windowSnapshots(*owned_, ownedF_);
    ownedFValid_ = true;
  }
  const auto norms = ownRowScores(*U_, ownedF_, owned_->numRows(), cf, false);
  double local[2] = {0.0, 0.0}, global[2] = {0.0, 0.0};
  for (double v : norms) local[0] += v * v;
  for (double v : ownedF_) local[1] += v * v;
  Teuchos::reduceAll(*U_->getMap()->getComm(), Teuchos::REDUCE_SUM, 2, local, global);
  return {std::sqrt(global[0]), std::sqrt(global[1])};
}

// P_{j+1} (alg:SP-ADEIM line 11): greedy DEIM or QDEIM from U_{j+1}, or Peher15's partial update
// of the rows of the pointUpdates most rotated columns; then the weights and the sample mesh.
double GpAdeimModel::moveInterpolationRows(const std::vector<double>& rotation) {
  std::vector<GO> P;
  if (opt_.indices == "partial") {
    Teuchos::TimeMonitor tm(phase("indices: selection"));
    std::vector<int> order(m_);
    for (int i = 0; i < m_; ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return rotation[a] > rotation[b]; });
    order.resize(opt_.pointUpdates);
    P = replaceDeimIndices(*U_, P_, order);
  } else {
    P = timedIndices(*U_, m_, opt_.indices);
  }
  DeimWeights info;
  replaceRows(interpolationKernel(*system_, *Arows_, *U_, P, rows().sample(), &info));
  P_ = rows().sample().rows;
  // P_{j+1}^T U_{j+1}, gathered for the weights: the next update's interpolation matrix (U and P
  // do not change in between), so that update needs no gather of its own.
  PtU_.shape(m_, m_);
  for (int j = 0; j < m_; ++j)
    for (int i = 0; i < m_; ++i) PtU_(i, j) = info.pointRows[i + static_cast<size_t>(m_) * j];
  return info.conditionNumber;
}

// The update moved column i of U by S a b_i^T (b_i the i-th row of b, only the rows S change):
// its relative change ||a b_i^T|| / ||u_i^{j+1}||, the "rotation" by which Peher15 picks the
// interpolation rows to re-choose. One collective (the column norms).
std::vector<double> GpAdeimModel::columnRotations(const AdeimUpdate& up) const {
  std::vector<double> norms(m_), out(m_);
  U_->norm2(Teuchos::ArrayView<double>(norms));
  DenseMatrix ata(up.rank, up.rank);
  ata.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, up.a, up.a, 0.0);
  for (int i = 0; i < m_; ++i) {
    double q = 0.0;  // b_i^T (a^T a) b_i
    for (int x = 0; x < up.rank; ++x)
      for (int y = 0; y < up.rank; ++y) q += up.b(i, x) * ata(x, y) * up.b(i, y);
    out[i] = norms[i] > 0.0 ? std::sqrt(std::max(q, 0.0)) / norms[i] : 0.0;
  }
  return out;
}

// U <- U T, an orthonormal basis of the same span (so the same DEIM projection for a given P),
// from the m x m Gram matrix G = U^T U (each rank's SYRK on its rows, one sum-reduction). For
// greedy and QDEIM index selection the columns come in column-pivoted QR order: the pivoted
// Cholesky factorization Pi^T G Pi = R^T R (LAPACK PSTRF) orders them as column-pivoted QR of U
// would (largest remaining norm first), and U Pi R^{-1} is a column permutation and a TRMM (half a
// GEMM's flops). For the partial point update, whose index i belongs to column i,
// T = V diag(lambda)^{-1/2} V^T (Loewdin, the symmetric eigenproblem by SYEVD) keeps each column
// nearest to its former self. Collective.
void GpAdeimModel::orthonormalizeBasis() {
  if (Unext_.is_null()) Unext_ = rcp(new MultiVector(U_->getMap(), m_));
  auto u = U_->getLocalViewHost(Tpetra::Access::ReadOnly);
  auto q = Unext_->getLocalViewHost(Tpetra::Access::OverwriteAll);
  const int nl = static_cast<int>(u.extent(0)), ldu = std::max<int>(1, static_cast<int>(u.stride(1))),
            ldq = std::max<int>(1, static_cast<int>(q.stride(1)));
  Teuchos::BLAS<int, double> blas;
  DenseMatrix G(m_, m_), Gd(m_, m_);
  if (nl > 0) blas.SYRK(Teuchos::UPPER_TRI, Teuchos::TRANS, m_, nl, 1.0, u.data(), ldu, 0.0, G.values(), G.stride());
  Teuchos::reduceAll(*U_->getMap()->getComm(), Teuchos::REDUCE_SUM, m_ * m_, G.values(), Gd.values());
  for (int j = 0; j < m_; ++j)
    for (int i = j + 1; i < m_; ++i) Gd(i, j) = Gd(j, i);
  if (opt_.indices == "partial") {
    const std::vector<double> lambda = symmetricEigen(m_, Gd.values(), true, "GP-ADEIM re-orthonormalization");
    GPHR_REQUIRE(lambda[0] > 0.0, SolverError, "GP-ADEIM: the updated DEIM basis is rank-deficient (Gram eigenvalues "
                 "down to ", lambda[0], ")");
    DenseMatrix T(m_, m_);
    for (int j = 0; j < m_; ++j)
      for (int i = 0; i < m_; ++i) {
        double sum = 0.0;
        for (int l = 0; l < m_; ++l) sum += Gd(i, l) * Gd(j, l) / std::sqrt(lambda[l]);
        T(i, j) = sum;
      }
    if (nl > 0)
      blas.GEMM(Teuchos::NO_TRANS, Teuchos::NO_TRANS, nl, m_, m_, 1.0, u.data(), ldu, T.values(), T.stride(), 0.0,
                q.data(), ldq);
  } else {
    const PivotedCholesky pc = pivotedCholeskyInverse(Gd);
    GPHR_REQUIRE(pc.rank == m_, SolverError, "GP-ADEIM: the updated DEIM basis is rank-deficient (pivoted Cholesky "
                 "of its Gram matrix stops at rank ", pc.rank, " of ", m_, ")");
    for (int j = 0; j < m_; ++j) std::copy_n(u.data() + static_cast<size_t>(ldu) * pc.perm[j], nl,
                                             q.data() + static_cast<size_t>(ldq) * j);
    if (nl > 0)
      blas.TRMM(Teuchos::RIGHT_SIDE, Teuchos::UPPER_TRI, Teuchos::NO_TRANS, Teuchos::NON_UNIT_DIAG, nl, m_, 1.0,
                pc.Rinv.values(), pc.Rinv.stride(), q.data(), ldq);
  }
  u = decltype(u)();  // release the views before the swap
  q = decltype(q)();
  U_->swap(*Unext_);
}

RCP<MultiVector> initialAdeimBasis(RCP<const HamiltonianSystem> system, const Vector& y0, const MultiVector& A,
                                   const Teuchos::ParameterList& integrator, double dt, int delta0, int m) {
  const GO d = static_cast<GO>(system->nonlinearTerm().numTerms());
  GPHR_REQUIRE(m >= 1 && m <= d, InputError, "GP-ADEIM: m = ", m, " is not available: G has d = ", d,
               " rows (allowed: 1 to d)");
  FullModelIntegrator integ(system, integrator);
  Vector y(y0, Teuchos::Copy);
  auto states = rcp(new MultiVector(system->map(), delta0 + 1));
  const std::function<void(long, double, const Vector&)> keep = [&](long j, double, const Vector& yj) {
    Tpetra::deep_copy(*states->getVectorNonConst(j), yj);
  };
  // The one observed loop: a non-finite state never becomes a snapshot of U_0.
  const SimulationStats sim = observedTimeLoop(integ, y, dt, delta0, keep);
  GPHR_REQUIRE(sim.ok(), SolverError, "the first ", delta0, " full-model steps (adeim.initialWindow): ", sim.reason);
  DeimBasisOptions opt;
  opt.maxRank = m;
  opt.svd = "randomized";
  opt.gramProjection = false;
  opt.powerIterations = 0;
  const DeimBasis basis = computeDeimBasis({system}, {states}, A, opt);
  GPHR_REQUIRE(static_cast<int>(basis.U->getNumVectors()) >= m, InputError, "GP-ADEIM: the first ", delta0,
               " full-model steps give ", basis.U->getNumVectors(), " independent reduced-Jacobian directions, fewer than m = ",
               m, " (raise adeim.initialWindow, lower m, or use adeim.initialBasis = training)");
  return basis.U;
}

}  // namespace gphr
