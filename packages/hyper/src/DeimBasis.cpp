#include "gphr/hyper/DeimBasis.hpp"

#include <Teuchos_BLAS.hpp>
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_LAPACK.hpp>

#include <cmath>
#include <limits>
#include <random>

#include "gphr/core/CacheKey.hpp"
#include "gphr/core/Error.hpp"
#include "gphr/core/ParameterValidation.hpp"
#include "gphr/hyper/JacobianSnapshots.hpp"
#include "gphr/reduction/DenseQr.hpp"
#include "gphr/reduction/DenseSvd.hpp"
#include "gphr/reduction/StreamingPod.hpp"
#include "gphr/reduction/SymmetricEigen.hpp"

namespace gphr {

namespace {

void checkInputs(const SystemSet& systems,
                 const SnapshotSet& states, const DeimBasisOptions& opt) {
  GPHR_REQUIRE(!systems.empty() && systems.size() == states.size(), InputError, "DEIM basis: ", systems.size(),
               " systems for ", states.size(), " snapshot sets (need one per training parameter)");
  GPHR_REQUIRE(opt.snapshotEvery >= 1, InputError, "DEIM basis: snapshotEvery = ", opt.snapshotEvery,
               " (allowed: >= 1)");
  GPHR_REQUIRE(opt.svd == "exact" || opt.svd == "randomized", InputError, "DEIM basis: svd '", opt.svd,
               "' is not one of 'exact', 'randomized'");
}

void requireNonzero(long used, int rank) {
  GPHR_REQUIRE(rank > 0, InputError, "DEIM basis: the ", used,
               " reduced-Jacobian snapshots are all zero (a linear problem, e.g. eps = 0, has nothing to hyper-reduce)");
}

// B = Q^T M_J's leading singular values (descending, at most maxRank, above the route's floor) and
// left singular vectors W (cols x kept, column-major), from C_s = J_s^T Q (r x cols, column-major,
// replicated), which each(use) hands to use(C_s) one snapshot at a time.
struct Projection {
  std::vector<double> sigma;
  std::vector<Scalar> W;
};

// B B^T = sum_s C_s^T C_s (cols x cols, LAPACK SYEVD: small and dense), sigma = sqrt(lambda):
// one small GEMM per snapshot, but the Gram matrix resolves sigma only to ~1e-7 sigma_1.
template <class Each>
Projection gramProjection(int cols, int r, int maxRank, Each&& each) {
  Teuchos::BLAS<int, double> blas;
  std::vector<Scalar> G(static_cast<size_t>(cols) * cols, 0.0);
  each([&](const std::vector<Scalar>& C) {
    blas.GEMM(Teuchos::TRANS, Teuchos::NO_TRANS, cols, cols, r, 1.0, C.data(), r, C.data(), r, 1.0, G.data(), cols);
  });
  const std::vector<double> lambda = symmetricEigen(cols, G.data(), true, "DEIM basis");
  const double floor = 1e-7 * std::sqrt(std::max(lambda[cols - 1], 0.0));  // Gram: sqrt(eps) resolution
  Projection p;
  p.W.resize(static_cast<size_t>(cols) * cols);
  for (int j = cols - 1; j >= 0 && static_cast<int>(p.sigma.size()) < maxRank; --j) {
    const double sigma = std::sqrt(std::max(lambda[j], 0.0));
    if (sigma <= floor || sigma == 0.0) break;
    std::copy_n(G.data() + static_cast<size_t>(cols) * j, cols, p.W.data() + static_cast<size_t>(cols) * p.sigma.size());
    p.sigma.push_back(sigma);
  }
  return p;
}

// B^T = [C_1; C_2; ...] = Q_B R, its R accumulated by a blocked QR of [R; the next snapshots'
// rows] (denseQrFactorR, ~4 cols rows at a time), and B = R^T Q_B^T: B's singular values are R's
// and its left singular vectors R's right ones. Resolves sigma to ~eps sigma_1; the floor is
// (number of columns) eps sigma_1: this route makes GP-ADEIM's initial basis U_0 from its first
// delta0 steps (gramProjection = false), whose m the user fixes; the training DEIM basis takes the
// Gram route (floor 1e-7) or the exact one (kDeimRankFloor).
template <class Each>
Projection qrProjection(int cols, int r, int maxRank, Each&& each) {
  const int batch = std::max(1, 4 * cols / std::max(r, 1)), ld = cols + batch * r;
  std::vector<Scalar> stack(static_cast<size_t>(ld) * cols, 0.0), R(static_cast<size_t>(cols) * cols, 0.0);
  int filled = 0;
  auto fold = [&] {  // R <- the R factor of [R; the filled rows]
    for (int j = 0; j < cols; ++j)
      std::copy_n(R.data() + static_cast<size_t>(cols) * j, cols, stack.data() + static_cast<size_t>(ld) * j);
    denseQrFactorR(cols + filled * r, cols, stack.data(), ld, R.data(), cols, "DEIM basis");
    filled = 0;
  };
  each([&](const std::vector<Scalar>& C) {
    for (int j = 0; j < cols; ++j)  // the next r rows of B^T
      std::copy_n(C.data() + static_cast<size_t>(r) * j, r,
                  stack.data() + static_cast<size_t>(ld) * j + cols + static_cast<size_t>(filled) * r);
    if (++filled == batch) fold();
  });
  if (filled > 0) fold();
  std::vector<double> sigma(cols), U(static_cast<size_t>(cols) * cols), Vt(static_cast<size_t>(cols) * cols);
  denseThinSvd(cols, cols, R.data(), cols, sigma.data(), U.data(), cols, Vt.data(), cols, true, "DEIM basis");
  const double floor = std::max(cols, r) * std::numeric_limits<double>::epsilon() * sigma[0];
  Projection p;
  p.W.resize(static_cast<size_t>(cols) * cols);
  for (int j = 0; j < cols && static_cast<int>(p.sigma.size()) < maxRank; ++j) {
    if (sigma[j] <= floor || sigma[j] == 0.0) break;
    for (int a = 0; a < cols; ++a) p.W[a + static_cast<size_t>(cols) * j] = Vt[j + static_cast<size_t>(cols) * a];
    p.sigma.push_back(sigma[j]);
  }
  return p;
}

// Randomized range finder (Halko, Martinsson & Tropp 2011, Alg. 4.3/4.4) over the streamed M_J:
//   Y = M_J Omega (Omega of random signs, regenerated per snapshot from a seed: the same on any rank
//   count), q power passes Y = M_J M_J^T Q, Q = orth(Y), then the SVD of B = Q^T M_J by its Gram
//   matrix or by the R factor of B^T (gramProjection, qrProjection above), U = Q W.
// Each pass regenerates the snapshots (cheap: one kernel evaluation each); nothing of size
// d x (2k states) is held. A power pass and the Gram matrix each square sigma: values below ~1e-7
// sigma_1 are then not resolved, far below the DEIM sizes worth using for a training basis.
class RangeFinder {
 public:
  RangeFinder(const SystemSet& systems, const SnapshotSet& states, const MultiVector& A, const DeimBasisOptions& opt,
              int maxRank)
      : systems_(systems), states_(states), A_(A), opt_(opt), rowMap_(systems[0]->nonlinearTerm().rowMap()),
        r_(static_cast<int>(A.getNumVectors())), nl_(static_cast<LO>(rowMap_->getNodeNumElements())),
        ell_(static_cast<int>(std::min<GO>(rowMap_->getGlobalNumElements(), maxRank + opt.oversampling))),
        jac_(static_cast<size_t>(nl_) * r_), ct_(static_cast<size_t>(r_) * ell_), ctSum_(ct_.size()), Y_(rowMap_, ell_) {
    GPHR_REQUIRE(Y_.isConstantStride() && (nl_ == 0 || Y_.getStride() == static_cast<size_t>(nl_)), InputError,
                 "DEIM basis: unexpected MultiVector layout");
  }

  // Pass 0: Y = sum_s J_s Omega_s.
  // Omega_s has random signs (Rademacher) rather than Gaussian entries: the range finder's
  // guarantees hold for both (HMT11 Sec. 4.6; Martinsson & Tropp 2020, Sec. 9) and the GEMM is the
  // same, but 64 signs come from one 64-bit draw: at the paper's NLS size drawing Gaussian
  // Omega_s (2k x ell = 48,000 numbers per snapshot, 1661 snapshots) took 2.2 ms a snapshot,
  // ~3.6 s of the DEIM offline time on every rank.
  void sketch() {
    std::vector<Scalar> omega(static_cast<size_t>(r_) * ell_);
    used_ = forEachJacobianSnapshot(systems_, states_, A_, opt_.snapshotEvery, jac_, [&](const auto& J, long s) {
      std::mt19937_64 rng(opt_.seed + 0x9E3779B97F4A7C15ull * static_cast<unsigned long long>(s + 1));
      for (size_t i = 0; i < omega.size(); i += 64) {
        const unsigned long long bits = rng();
        for (size_t b = 0; b < 64 && i + b < omega.size(); ++b) omega[i + b] = (bits >> b) & 1ull ? 1.0 : -1.0;
      }
      if (nl_ > 0)
        blas_.GEMM(Teuchos::TRANS, Teuchos::NO_TRANS, nl_, ell_, r_, 1.0, J.data(), r_, omega.data(), r_, 1.0, yData(), nl_);
    });
  }

  // Q = orth(Y) (StreamingPod: a Householder QR of each rank's rows, the R factors reduced, one small SVD).
  RCP<MultiVector> orth() {
    StreamingPod q(rowMap_, ell_, ell_, -1.0);
    q.add(Y_);
    requireNonzero(used_, q.rank());
    return rcp(new MultiVector(q.leftVectors(), Teuchos::Copy));
  }

  // A power pass: Y = M M^T Q.
  void powerPass(const MultiVector& Q) {
    Y_ = MultiVector(rowMap_, Q.getNumVectors());
    forEachJacobianSnapshot(systems_, states_, A_, opt_.snapshotEvery, jac_, [&](const auto& J, long) {
      const int cols = project(Q, J);
      if (nl_ > 0)
        blas_.GEMM(Teuchos::TRANS, Teuchos::NO_TRANS, nl_, cols, r_, 1.0, J.data(), r_, ctSum_.data(), r_, 1.0, yData(), nl_);
    });
  }

  // The last pass: C_s = J_s^T Q for every snapshot handed to the projection (and M_J's energy
  // summed), then U = Q W.
  DeimBasis basis(const MultiVector& Q, int maxRank) {
    const int cols = static_cast<int>(Q.getNumVectors());
    double energy = 0.0;
    auto eachProjection = [&](auto&& use) {
      forEachJacobianSnapshot(systems_, states_, A_, opt_.snapshotEvery, jac_, [&](const auto& J, long) {
        project(Q, J);
        use(ctSum_);
        energy += squaredNorm(J);
      });
    };
    const Projection p = opt_.gramProjection ? gramProjection(cols, r_, maxRank, eachProjection)
                                             : qrProjection(cols, r_, maxRank, eachProjection);
    const int keep = static_cast<int>(p.sigma.size());
    requireNonzero(used_, keep);
    auto local = rcp(new Map(cols, 0, rowMap_->getComm(), Tpetra::LocallyReplicated));
    MultiVector Wk(local, keep);
    {
      auto w = Wk.getLocalViewHost(Tpetra::Access::OverwriteAll);
      for (int c = 0; c < keep; ++c)
        for (int a = 0; a < cols; ++a) w(a, c) = p.W[a + static_cast<size_t>(cols) * c];
    }
    DeimBasis out;
    out.singularValues = p.sigma;
    out.U = rcp(new MultiVector(rowMap_, keep));
    out.U->multiply(Teuchos::NO_TRANS, Teuchos::NO_TRANS, 1.0, Q, Wk, 0.0);
    out.snapshots = used_;
    out.energy = energy;
    return out;
  }

 private:
  double* yData() { return Y_.getLocalViewHost(Tpetra::Access::ReadWrite).data(); }  // column-major, stride nl

  // C_s = J_s^T Q (r x cols), summed over the ranks into ctSum_; returns cols.
  int project(const MultiVector& Q, const std::vector<Scalar>& J) {
    const int cols = static_cast<int>(Q.getNumVectors());
    std::fill(ct_.begin(), ct_.end(), 0.0);
    auto qv = Q.getLocalViewHost(Tpetra::Access::ReadOnly);
    if (nl_ > 0)
      blas_.GEMM(Teuchos::NO_TRANS, Teuchos::NO_TRANS, r_, cols, nl_, 1.0, J.data(), r_, qv.data(), nl_, 0.0, ct_.data(), r_);
    Teuchos::reduceAll(*rowMap_->getComm(), Teuchos::REDUCE_SUM, r_ * cols, ct_.data(), ctSum_.data());
    return cols;
  }

  // ||J_s||_F^2 summed over the ranks.
  double squaredNorm(const std::vector<Scalar>& J) const {
    double local = 0.0, global = 0.0;
    for (double x : J) local += x * x;
    Teuchos::reduceAll(*rowMap_->getComm(), Teuchos::REDUCE_SUM, local, Teuchos::outArg(global));
    return global;
  }

  const SystemSet& systems_;
  const SnapshotSet& states_;
  const MultiVector& A_;
  const DeimBasisOptions& opt_;
  RCP<const Map> rowMap_;
  int r_;
  LO nl_;
  int ell_;
  Teuchos::BLAS<int, double> blas_;
  std::vector<Scalar> jac_, ct_, ctSum_;
  MultiVector Y_;
  long used_ = 0;
};

DeimBasis randomizedDeimBasis(const SystemSet& systems, const SnapshotSet& states, const MultiVector& A,
                              const DeimBasisOptions& opt, int maxRank) {
  RangeFinder finder(systems, states, A, opt, maxRank);
  finder.sketch();
  RCP<MultiVector> Q = finder.orth();
  for (int pass = 0; pass < opt.powerIterations; ++pass) {
    finder.powerPass(*Q);
    Q = finder.orth();
  }
  return finder.basis(*Q, maxRank);
}

}  // namespace

int deimMaxRank(const DeimBasisOptions& opt, GO d) {
  const int wanted = opt.maxRank > 0    ? opt.maxRank
                     : opt.largestM > 0 ? opt.largestM + kDeimRankMargin
                                        : kDefaultDeimRank;
  return static_cast<int>(std::min<GO>(d, wanted));
}

DeimChunks deimChunks(const SnapshotSet& states, const DeimBasisOptions& opt, int r, int maxRank) {
  GPHR_REQUIRE(opt.chunkSnapshots >= 0, InputError, "DEIM basis: chunkSnapshots = ", opt.chunkSnapshots,
               " (allowed: 0 for automatic, or >= 1)");
  DeimChunks c;
  c.snapshots = usedSnapshotCount(states, opt.snapshotEvery);
  const long target = opt.chunkSnapshots > 0
                          ? opt.chunkSnapshots
                          : std::max<long>(1, (static_cast<long>(kChunkColumnsPerRank) * maxRank + r - 1) / std::max(r, 1));
  const long chunks = std::max<long>(1, (c.snapshots + target - 1) / target);
  c.perChunk = std::max<long>(1, (c.snapshots + chunks - 1) / chunks);  // evened out: chunk sizes differ by < chunks
  return c;
}

namespace {

// The streaming POD of the reduced-Jacobian snapshots in `range`; `snapshots` gets their count.
StreamingPod chunkPod(const SystemSet& systems, const SnapshotSet& states,
                      const MultiVector& A, const DeimBasisOptions& opt, int maxRank, SnapshotRange range,
                      long& snapshots, ReducedStateCache* cache = nullptr) {
  const RCP<const Map> rowMap = systems[0]->nonlinearTerm().rowMap();
  const int r = static_cast<int>(A.getNumVectors());
  const LO nl = static_cast<LO>(rowMap->getNodeNumElements());
  // Snapshots per POD step (the same on any rank count): a step costs O(d (rank + columns)^2), so
  // about maxRank new columns per step balances the number of steps against their size.
  const int perBlock = opt.blockSnapshots > 0 ? opt.blockSnapshots : std::max(1, (maxRank + r - 1) / r);
  StreamingPod pod(rowMap, maxRank, perBlock * r, kDeimRankFloor, podRouteFromName(opt.podRoute));
  MultiVector block(rowMap, static_cast<size_t>(perBlock) * r);
  std::vector<Scalar> jac(static_cast<size_t>(nl) * r);
  int filled = 0;
  auto flush = [&] {
    if (filled == perBlock) pod.add(block);
    else if (filled > 0) pod.add(*block.subView(Teuchos::Range1D(0, static_cast<size_t>(filled) * r - 1)));
    filled = 0;
  };
  snapshots = forEachJacobianSnapshotIn(systems, states, A, opt.snapshotEvery, range, jac, [&](const auto& J, long) {
    auto b = block.getLocalViewHost(Tpetra::Access::ReadWrite);
    for (LO i = 0; i < nl; ++i)
      for (int a = 0; a < r; ++a) b(i, static_cast<size_t>(filled) * r + a) = J[static_cast<size_t>(i) * r + a];
    if (++filled == perBlock) flush();
  }, cache);
  flush();
  return pod;
}

DeimChunkModes statisticsOf(const StreamingPod& pod, long snapshots) {
  DeimChunkModes out;
  out.rank = pod.rank();
  out.energy = pod.totalEnergy();
  out.snapshots = snapshots;
  out.podSteps = pod.steps();
  return out;
}

// The basis of `pod` (the root, or the only chunk); `stats`: the snapshots' count and energy and
// the steps of the chunk PODs below it (none for the only chunk), to which pod's own are added.
DeimBasis basisOf(const StreamingPod& pod, const DeimChunkModes& stats) {
  requireNonzero(stats.snapshots, pod.rank());
  DeimBasis out;
  out.singularValues = pod.singularValues();
  out.snapshots = stats.snapshots;
  out.energy = stats.energy;
  out.U = rcp(new MultiVector(pod.leftVectors(), Teuchos::Copy));
  (out.podSteps = stats.podSteps) += pod.steps();
  return out;
}

void addStatistics(DeimChunkModes& sum, const DeimChunkModes& c) {
  sum.energy += c.energy, sum.snapshots += c.snapshots;
  sum.podSteps += c.podSteps;
}

}  // namespace

DeimChunkModes deimChunkModes(const SystemSet& systems, const SnapshotSet& states,
                              const MultiVector& A, const DeimBasisOptions& opt, int maxRank, SnapshotRange range,
                              ReducedStateCache* cache) {
  long snapshots = 0;
  const StreamingPod pod = chunkPod(systems, states, A, opt, maxRank, range, snapshots, cache);
  DeimChunkModes out = statisticsOf(pod, snapshots);
  out.modes = rcp(new MultiVector(pod.leftVectors(), Teuchos::Copy));
  if (out.rank > 0) {
    std::vector<double> sigma(pod.singularValues());
    out.modes->scale(Teuchos::ArrayView<const double>(sigma));
  }
  return out;
}

// One step per chunk (blockColumns = maxRank >= a chunk's rank): maxRank carried + at most maxRank
// new columns, the size of a chunk's own steps.
DeimRootPod::DeimRootPod(RCP<const Map> rowMap, const DeimBasisOptions& opt, int maxRank)
    : pod_(std::move(rowMap), maxRank, maxRank, kDeimRankFloor, podRouteFromName(opt.podRoute)) {}

void DeimRootPod::add(const MultiVector& modes, const DeimChunkModes& stats) {
  addStatistics(sum_, stats);
  if (stats.rank > 0) pod_.add(*modes.subView(Teuchos::Range1D(0, stats.rank - 1)));
}

DeimBasis DeimRootPod::basis() const { return basisOf(pod_, sum_); }

void DeimRootPod::restore(const StreamingPod::State& state, const DeimChunkModes& statistics) {
  pod_.restore(state);
  sum_ = statistics;
  sum_.modes = Teuchos::null;
}

DeimBasis computeDeimBasis(const SystemSet& systems,
                           const SnapshotSet& states, const MultiVector& A,
                           const DeimBasisOptions& opt) {
  checkInputs(systems, states, opt);
  const RCP<const Map> rowMap = systems[0]->nonlinearTerm().rowMap();
  const int r = static_cast<int>(A.getNumVectors());
  const int maxRank = deimMaxRank(opt, static_cast<GO>(rowMap->getGlobalNumElements()));
  if (opt.svd == "randomized") return randomizedDeimBasis(systems, states, A, opt, maxRank);
  const DeimChunks chunks = deimChunks(states, opt, r, maxRank);
  if (chunks.count() == 1) {  // one chunk: its own POD is the basis, no root
    long snapshots = 0;
    const StreamingPod pod = chunkPod(systems, states, A, opt, maxRank, chunks.range(0), snapshots);
    DeimChunkModes none;  // no chunk PODs below this one: basisOf adds its own steps
    none.energy = pod.totalEnergy(), none.snapshots = snapshots;
    return basisOf(pod, none);
  }
  DeimRootPod root(rowMap, opt, maxRank);
  ReducedStateCache blocks;  // consecutive chunks share blocks: each read once
  for (int q = 0; q < chunks.count(); ++q) {
    const DeimChunkModes c = deimChunkModes(systems, states, A, opt, maxRank, chunks.range(q), &blocks);
    root.add(*c.modes, c);
  }
  return root.basis();
}

Teuchos::ParameterList deimBasisValidParameters() {
  Teuchos::ParameterList hyp("hyper");
  setIntParameter(hyp, "snapshotEvery", 1, 1, 1000000,
                  "reduced-Jacobian snapshot at every N-th stored training state (the paper: 20)");
  setChoiceParameter(hyp, "indices", "deim", Teuchos::tuple<std::string>("deim", "qdeim"),
                     "interpolation indices: greedy DEIM (Chaturantabut-Sorensen) or QDEIM (pivoted QR)");
  const auto routes = podRouteNames();
  setIntParameter(hyp, "maxRank", 0, 0, 1000000,
                  "singular triplets kept by the streaming POD of the DEIM snapshots; 0: max(m) + 32, at most d");
  setChoiceParameter(hyp, "svd", "exact", Teuchos::tuple<std::string>("exact", "randomized"),
                     "DEIM basis: exact streaming POD (incremental TSQR + SVD) or the randomized range finder (HMT11)");
  setIntParameter(hyp, "oversampling", 10, 0, 10000, "randomized: extra columns of the sketch");
  setIntParameter(hyp, "powerIterations", 1, 0, 10, "randomized: power iterations (one streamed pass each)");
  setIntParameter(hyp, "blockSnapshots", 0, 0, 100000,
                  "reduced-Jacobian snapshots per incremental POD step; 0: about maxRank columns per step");
  setIntParameter(hyp, "chunkSnapshots", 0, 0, 100000000,
                  "svd exact: reduced-Jacobian snapshots per chunk of the hierarchical POD (each chunk POD'd on its "
                  "own, by the rank groups side by side, then one POD of the chunks' modes); 0: about 32 maxRank "
                  "columns per chunk, equal chunks; a number >= the snapshots used: one chunk, the plain streaming POD");
  setIntParameter(hyp, "groupSize", 0, 0, 1000000,
                  "svd exact: ranks per rank group of the DEIM basis stage (the groups POD the chunks side by side); "
                  "0: one group per chunk, each with at most 2^18 state rows per rank; >= the ranks: all ranks together");
  setChoiceParameter(hyp, "podRoute", "auto", Teuchos::Array<std::string>(routes.begin(), routes.end()), "svd exact: the incremental SVD's step route, as reduction.podRoute");
  setChoiceParameter(hyp, "deimSnapshots", "full", Teuchos::tuple<std::string>("full", "projected"),
                     "snapshots of the classic DEIM baseline (method deim): full = grad N(y) - grad N(y0) at the full "
                     "model's training states (Chaturantabut-Sorensen with the shift of paper Sec. 3.3; the model adds "
                     "grad N(y0) back), projected = grad N(y0 + A A^T (y - y0)) at the training states projected on "
                     "the reduced basis, unshifted");
  return hyp;
}

std::string deimBasisCacheKey(const DeimBasisOptions& o) {
  return CacheKey("deim basis", 3)
      .add("maxRank", deimMaxRank(o, std::numeric_limits<GO>::max()))
      .add("snapshotEvery", o.snapshotEvery)
      .add("blockSnapshots", o.blockSnapshots)
      .add("chunkSnapshots", o.chunkSnapshots)
      .add("svd", o.svd)
      .add("podRoute", o.podRoute)
      .add("oversampling", o.oversampling)
      .add("powerIterations", o.powerIterations)
      .add("gramProjection", o.gramProjection)
      .add("seed", o.seed)
      .str();
}

DeimBasisOptions deimBasisOptionsFrom(const Teuchos::ParameterList& hyp, int largestM) {
  DeimBasisOptions o;
  o.snapshotEvery = hyp.get<int>("snapshotEvery");
  o.blockSnapshots = hyp.get<int>("blockSnapshots");
  o.chunkSnapshots = hyp.get<int>("chunkSnapshots");
  o.groupSize = hyp.get<int>("groupSize");
  o.svd = hyp.get<std::string>("svd");
  o.oversampling = hyp.get<int>("oversampling");
  o.powerIterations = hyp.get<int>("powerIterations");
  o.podRoute = hyp.get<std::string>("podRoute");
  o.maxRank = hyp.get<int>("maxRank");
  o.largestM = largestM;
  return o;
}

}  // namespace gphr
