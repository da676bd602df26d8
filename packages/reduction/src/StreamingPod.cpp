#include "gphr/reduction/StreamingPod.hpp"

#include <Teuchos_BLAS.hpp>
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_LAPACK.hpp>
#include <Teuchos_SerialDenseMatrix.hpp>
#include <Tpetra_TsqrAdaptor.hpp>

#include <cmath>
#include <limits>

#include "gphr/core/Error.hpp"
#include "gphr/core/ReplicatedGather.hpp"
#include "gphr/reduction/DenseSvd.hpp"
#include "gphr/reduction/TreeTsqr.hpp"

namespace gphr {

PodRoute podRouteFromName(const std::string& name) {
  if (name == "auto") return PodRoute::Auto;
  if (name == "tsqr") return PodRoute::Tsqr;
  if (name == "stacked") return PodRoute::Stacked;
  if (name == "tree") return PodRoute::Tree;
  GPHR_REQUIRE(name == "replicated", InputError, "streaming POD: podRoute '", name,
               "' is not one of 'auto', 'tsqr', 'stacked', 'tree', 'replicated'");
  return PodRoute::Replicated;
}

std::vector<std::string> podRouteNames() { return {"auto", "tsqr", "stacked", "tree", "replicated"}; }

// auto: the tree from 2 ranks on. With TPQRT at its levels its small factorizations cost 0.7x the
// stacked route's GESDD at p = 2 and 0.4x at 4 on one core, and whole steps (2048 rows per rank,
// c = 512) were 1.13-1.28x faster on 2 ranks, 1.52x on 3, 1.80x on 4 (bench/pod_tree_micro.cpp;
// doc/design.md, 'Symplectic bases and the streaming POD'). One rank: both the same work.
PodRoute stepRoute(PodRoute route, int ranks) {
  if (route != PodRoute::Auto) return route;
  return ranks >= kTreeRouteFromRanks ? PodRoute::Tree : PodRoute::Stacked;
}

StreamingPod::StreamingPod(RCP<const Map> map, int maxRank, int blockColumns, double rankTolerance, PodRoute route)
    : map_(map), maxRank_(maxRank), blockColumns_(blockColumns), rankTolerance_(rankTolerance), route_(route) {
  GPHR_REQUIRE(blockColumns_ >= 1, InputError, "streaming POD: blockColumns = ", blockColumns_, " (allowed: >= 1)");
  const LO nl = static_cast<LO>(map_->getNodeNumElements());
  LO minLocal = 0;
  Teuchos::reduceAll(*map_->getComm(), Teuchos::REDUCE_MIN, nl, Teuchos::outArg(minLocal));
  cap_ = static_cast<int>(minLocal);
  const GO d = static_cast<GO>(map_->getGlobalNumElements());
  GPHR_REQUIRE(maxRank_ >= 1 && maxRank_ <= d, InputError, "streaming POD: maxRank = ", maxRank_,
               " is not allowed (allowed: 1 to the number of rows, ", d, ")");
  U_ = rcp(new MultiVector(map_, 1));
}

std::vector<double> columnSquaredNorms(const MultiVector& X) {
  const size_t n = X.getNumVectors();
  const int rows = static_cast<int>(X.getLocalLength());
  std::vector<double> mine(n, 0.0), all(n, 0.0);
  const Teuchos::BLAS<int, double> blas;
  for (size_t j = 0; j < n; ++j) {
    const Teuchos::ArrayRCP<const double> x = X.getData(j);
    if (rows > 0) mine[j] = blas.DOT(rows, x.getRawPtr(), 1, x.getRawPtr(), 1);
  }
  if (n > 0) Teuchos::reduceAll(*X.getMap()->getComm(), Teuchos::REDUCE_SUM, static_cast<int>(n), mine.data(), all.data());
  return all;
}

void StreamingPod::add(const MultiVector& X) {
  GPHR_REQUIRE(X.getMap()->isSameAs(*map_), InputError, "streaming POD: a block of ", X.getGlobalLength(),
               " rows does not match the POD's map of ", map_->getGlobalNumElements(), " rows");
  for (double x : columnSquaredNorms(X)) {
    GPHR_REQUIRE(std::isfinite(x), InputError, "streaming POD: a snapshot column is not finite (squared norm ", x,
                 ")");
    energy_ += x;
  }
  columns_ += static_cast<long>(X.getNumVectors());
  // Steps of blockColumns columns whatever the rank count, so that the truncations (and the
  // result) are the same on any number of ranks; each step takes the route of stepRoute.
  for (size_t c0 = 0; c0 < X.getNumVectors();) {
    const size_t c1 = std::min(X.getNumVectors(), c0 + static_cast<size_t>(blockColumns_));
    step(X, c0, c1);
    c0 = c1;
  }
}

StreamingPod::State StreamingPod::state() const {
  State s;
  s.U = U_;  // shared, not copied: every step makes a new U_ and never writes into the one before
  s.sigma = sigma_, s.energy = energy_, s.columns = columns_;
  s.steps = steps_;
  return s;
}

void StreamingPod::restore(const State& s) {
  const size_t r = s.sigma.size();
  GPHR_REQUIRE(s.U && s.U->getMap()->isSameAs(*map_) && s.U->getNumVectors() == std::max<size_t>(r, 1) &&
                   static_cast<int>(r) <= maxRank_,
               InputError, "streaming POD: a saved state of ", r, " singular values and ",
               s.U ? s.U->getNumVectors() : 0, " vectors of ", s.U ? s.U->getGlobalLength() : 0,
               " rows does not fit this POD (allowed: at most maxRank = ", maxRank_, " values, as many vectors, ",
               map_->getGlobalNumElements(), " rows)");
  for (size_t j = 0; j < r; ++j)
    GPHR_REQUIRE(std::isfinite(s.sigma[j]) && s.sigma[j] > 0.0 && (j == 0 || s.sigma[j] <= s.sigma[j - 1]), InputError,
                 "streaming POD: saved singular value ", j + 1, " is ", s.sigma[j],
                 " (allowed: finite, positive, not above the one before)");
  U_ = rcp(new MultiVector(*s.U, Teuchos::Copy));
  sigma_ = s.sigma, energy_ = s.energy, columns_ = s.columns;
  steps_ = s.steps;
}

namespace {
// Thin SVD of the m x n column-major matrix a (overwritten): S (min(m, n)) and the leading
// min(m, n) left singular vectors W (m x min(m, n), column-major). LAPACK GESVD.
void denseLeftSvd(int m, int n, double* a, int lda, std::vector<double>& S, std::vector<double>& W) {
  const int mn = std::min(m, n);
  S.resize(mn);
  W.resize(static_cast<size_t>(m) * mn);
  std::vector<double> Z(1), work(1);
  Teuchos::LAPACK<int, double> lapack;
  int info = 0;
  lapack.GESVD('S', 'N', m, n, a, lda, S.data(), W.data(), m, Z.data(), 1, work.data(), -1, nullptr, &info);
  work.resize(std::max(1, static_cast<int>(work[0])));
  lapack.GESVD('S', 'N', m, n, a, lda, S.data(), W.data(), m, Z.data(), 1, work.data(),
               static_cast<int>(work.size()), nullptr, &info);
  GPHR_REQUIRE(info == 0, SolverError, "streaming POD: LAPACK GESVD failed (info = ", info, ")");
}
}  // namespace

// Numerical rank: singular values above tol * sigma_1, by default n_cols * eps (LAPACK's rank
// convention: the rest is round-off of the data). Keeps at most maxRank.
int StreamingPod::truncate(const std::vector<double>& S, int nc) {
  int keep = 0;
  const double tol = rankTolerance_ >= 0.0 ? rankTolerance_ : nc * std::numeric_limits<double>::epsilon();
  const double floor = tol * (S.empty() ? 0.0 : S[0]);
  while (keep < std::min(static_cast<int>(S.size()), maxRank_) && S[keep] > floor && S[keep] > 0.0) ++keep;
  sigma_.assign(S.begin(), S.begin() + keep);
  return keep;
}

// The route where TSQR cannot go (carried + new columns > rows on some rank): Y gathered on every
// rank (d x nc numbers) and one LAPACK thin SVD there; each rank keeps its own rows of U.
void StreamingPod::replicatedStep(const MultiVector& Y) {
  const int nc = static_cast<int>(Y.getNumVectors());
  const GO d = static_cast<GO>(map_->getGlobalNumElements());
  std::vector<GO> all(d);
  for (GO i = 0; i < d; ++i) all[i] = map_->getMinAllGlobalIndex() + i;
  GPHR_REQUIRE(map_->getMaxAllGlobalIndex() - map_->getMinAllGlobalIndex() + 1 == d, InputError,
               "streaming POD: the replicated route needs global ids without gaps");
  const std::vector<double> rows = gatherRows(Y, all);  // d x nc row-major
  std::vector<double> a(static_cast<size_t>(d) * nc);
  for (GO i = 0; i < d; ++i)
    for (int j = 0; j < nc; ++j) a[i + static_cast<size_t>(d) * j] = rows[static_cast<size_t>(i) * nc + j];
  std::vector<double> S, W;
  denseLeftSvd(static_cast<int>(d), nc, a.data(), static_cast<int>(d), S, W);
  const int keep = truncate(S, nc);
  U_ = rcp(new MultiVector(map_, std::max(keep, 1)));
  auto u = U_->getLocalViewHost(Tpetra::Access::OverwriteAll);
  for (LO l = 0; l < static_cast<LO>(map_->getNodeNumElements()); ++l) {
    const GO i = map_->getGlobalElement(l) - map_->getMinAllGlobalIndex();
    for (int j = 0; j < keep; ++j) u(l, j) = W[i + static_cast<size_t>(d) * j];
  }
}

// U_p = Q_p [C; 0] for this rank's leaf QR and its block C of the small factor's left vectors,
// applied straight into U's storage. The old U was copied into the leaf's array already, so its
// storage takes the new one when it has the same width and nobody else holds it (a State shares
// U: a checkpoint's U is never overwritten); otherwise the old U goes before the new one is
// allocated: two rows x keep arrays fewer at the step's peak (the leaf's array, the new U and the
// caller's block). The leaf's array is kept for the next step (work_).
void StreamingPod::setLeftVectors(HouseholderQr& leaf, const std::vector<double>& C, int keep) {
  const int rows = leaf.rows();
  const size_t width = static_cast<size_t>(std::max(keep, 1));
  const bool reuse = keep > 0 && rows > 0 && U_.strong_count() == 1 && U_->getNumVectors() == width;
  if (!reuse) {
    U_ = Teuchos::null;
    U_ = rcp(new MultiVector(map_, width));
  }
  if (keep > 0 && rows > 0) {
    GPHR_REQUIRE(U_->isConstantStride() && U_->getStride() >= static_cast<size_t>(rows), InputError,
                 "streaming POD: unexpected MultiVector layout");
    auto u = U_->getLocalViewHost(Tpetra::Access::OverwriteAll);
    leaf.applyQInto(C, keep, u.data(), static_cast<int>(U_->getStride()));
  }
  work_ = leaf.releaseStorage();
}

// The stacked-QR route (a TSQR with LAPACK kernels and a flat reduction): each rank factors its
// own rows Y_p = Q_p R_p (HouseholderQr: GEQRT and TPQRT over chunks of its rows; R_p is
// min(rows_p, nc) x nc: a rank may hold fewer rows than columns), every rank holds the stack of
// all R_p (a sum-reduction of disjoint blocks, so exact) and takes its thin SVD by GESDD,
// stack = W S Z^T; then Y = blockdiag(Q_p) W S Z^T, and each rank forms its rows of
// U = Q_p W_p(:, 1:keep) (GEMQRT/TPMQRT). Work per rank: rows_p nc^2 for the local QR and its Q
// (these divide with the ranks) plus the stack's SVD, min(d, p nc) nc^2 (replicated):
// it scales while every rank holds several times nc rows, and where none does it costs about what
// the replicated route costs, with stack rows instead of d.
void StreamingPod::stackedStep(std::vector<double> y, int nc) {
  const int rows = static_cast<int>(map_->getNodeNumElements());
  const auto& comm = *map_->getComm();
  const int p = comm.getSize(), me = comm.getRank();
  HouseholderQr leaf(rows, nc, std::move(y));
  const int kp = leaf.k();
  // The stack: rank q's R factor at rows off[q] .. off[q] + k[q].
  std::vector<int> k(p, 0), off(p + 1, 0);
  Teuchos::gatherAll(comm, 1, &kp, p, k.data());
  for (int q = 0; q < p; ++q) off[q + 1] = off[q] + k[q];
  const int K = off[p];
  // The stack's reduction counts its entries in an int (MPI): p nc^2 of them, 2.6e9 at p = 4096,
  // nc = 800 (and 21 GB on every rank); the tree route holds nc^2.
  GPHR_REQUIRE(static_cast<double>(K) * nc <= std::numeric_limits<int>::max(), InputError,
               "streaming POD (stacked route): a stack of ", K, " x ", nc, " entries on ", p,
               " ranks exceeds an MPI count; allowed: podRoute 'auto' or 'tree'");
  std::vector<double> mine(static_cast<size_t>(K) * nc, 0.0), stack(mine.size());
  const std::vector<double> R = leaf.r();
  for (int j = 0; j < nc; ++j)
    std::copy_n(R.begin() + static_cast<size_t>(kp) * j, kp, mine.begin() + off[me] + static_cast<size_t>(K) * j);
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, static_cast<int>(mine.size()), mine.data(), stack.data());
  const int mn = std::min(K, nc);
  std::vector<double> S(mn), W(static_cast<size_t>(K) * mn), Zt(static_cast<size_t>(mn) * nc);
  denseThinSvd(K, nc, stack.data(), K, S.data(), W.data(), K, Zt.data(), mn, true, "streaming POD (stacked route)");
  const int keep = truncate(S, nc);
  std::vector<double> C(static_cast<size_t>(kp) * keep);
  for (int j = 0; j < keep; ++j)
    std::copy_n(W.begin() + off[me] + static_cast<size_t>(K) * j, kp, C.begin() + static_cast<size_t>(kp) * j);
  setLeftVectors(leaf, C, keep);
}

// The tree route (TSQR with a binary-tree reduction, TreeTsqr.hpp): each rank's rows by
// HouseholderQr as in the stacked route, the R factors reduced to rank 0 over ceil(log2 p) levels
// of QRs of two stacked nc x nc triangles (TPQRT), one GESDD of the root's R (at most nc x nc) on
// rank 0, its singular values broadcast (every rank truncates alike) and its left vectors carried
// back down the tree's Q factors to each rank's block. Beyond its own rows a rank does at most
// log2(p) small QRs and their Q's, and rank 0 one nc x nc SVD: none of it grows with p but the
// log2 p levels.
void StreamingPod::treeStep(std::vector<double> y, int nc) {
  const auto& comm = *map_->getComm();
  HouseholderQr leaf(static_cast<int>(map_->getNodeNumElements()), nc, std::move(y));
  TreeTsqr tree(comm, nc);
  int K = 0;
  std::vector<double> R = tree.reduce(leaf.r(), leaf.k(), &K);
  int mn = std::min(K, nc);
  std::vector<double> S, W;
  std::string failure;  // rank 0's SVD failure: the others learn it from mn = -1, not by waiting
  if (comm.getRank() == 0) {
    S.resize(mn), W.resize(static_cast<size_t>(K) * mn);
    std::vector<double> Zt(static_cast<size_t>(mn) * nc);
    try {
      denseThinSvd(K, nc, R.data(), std::max(K, 1), S.data(), W.data(), std::max(K, 1), Zt.data(), std::max(mn, 1),
                   true, "streaming POD (tree route)");
    } catch (const SolverError& e) {
      failure = e.what(), mn = -1;
    }
  }
  Teuchos::broadcast(comm, 0, Teuchos::outArg(mn));
  GPHR_REQUIRE(mn >= 0, SolverError, failure.empty() ? "streaming POD (tree route): the SVD failed on rank 0" : failure);
  S.resize(mn);
  if (mn > 0) Teuchos::broadcast(comm, 0, mn, S.data());
  const int keep = truncate(S, nc);
  W.resize(static_cast<size_t>(K) * keep);  // W's leading keep columns (column-major)
  setLeftVectors(leaf, tree.applyQ(std::move(W), keep), keep);
}

// Y = [U diag(sigma), X(:, c0:c1)], this rank's rows, straight into the column-major array the
// leaf QR factors in place: a MultiVector Y and its copy would be two more rows x nc arrays at the
// stage's peak. The array is the previous step's (every entry is written below): a fresh one per
// step paid its pages' faults and zeroing, 10 % of the SWE 256^2 DEIM basis on one rank (perf),
// more where ranks share a node's memory bandwidth.
std::vector<double> StreamingPod::leafColumns(const MultiVector& X, size_t c0, size_t c1) {
  const int r = rank(), b = static_cast<int>(c1 - c0);
  const size_t rows = map_->getNodeNumElements();
  std::vector<double> y = std::move(work_);
  if (y.size() < rows * (r + b)) {  // the rank still growing: a new array, nothing of the old copied
    std::vector<double>().swap(y);
    y.resize(rows * (r + b));
  }
  auto u = U_->getLocalViewHost(Tpetra::Access::ReadOnly);
  auto x = X.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (int j = 0; j < r; ++j)
    for (size_t i = 0; i < rows; ++i) y[i + rows * j] = sigma_[j] * u(i, j);
  for (int j = 0; j < b; ++j)
    for (size_t i = 0; i < rows; ++i) y[i + rows * (r + j)] = x(i, c0 + j);
  return y;
}

// The same Y as a MultiVector (the replicated and tsqr routes).
MultiVector StreamingPod::stepMatrix(const MultiVector& X, size_t c0, size_t c1) const {
  const int r = rank(), b = static_cast<int>(c1 - c0);
  MultiVector Y(map_, r + b);
  auto y = Y.getLocalViewHost(Tpetra::Access::OverwriteAll);
  auto u = U_->getLocalViewHost(Tpetra::Access::ReadOnly);
  auto x = X.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (size_t i = 0; i < y.extent(0); ++i) {
    for (int j = 0; j < r; ++j) y(i, j) = sigma_[j] * u(i, j);
    for (int j = 0; j < b; ++j) y(i, r + j) = x(i, c0 + j);
  }
  return Y;
}

// The tsqr route: Tpetra's TSQR (Y = Q R, Q explicit), then R's SVD on every rank.
void StreamingPod::tsqrStep(MultiVector& Y) {
  const int nc = static_cast<int>(Y.getNumVectors()), r = rank();
  // cap_ and nc are the same on every rank: all ranks refuse together.
  const GO d = static_cast<GO>(map_->getGlobalNumElements());
  GPHR_REQUIRE(nc <= cap_, InputError, "streaming POD: podRoute 'tsqr' cannot take a step of ", nc, " columns (", r,
               " carried + ", nc - r, " new): TSQR needs at most as many columns as rows on every rank, and on ",
               map_->getComm()->getSize(), " rank(s) the smallest holds ", cap_, " of the ", d,
               " rows; allowed: podRoute 'auto', 'stacked', 'tree' or 'replicated', ",
               d >= nc ? detail::concat("at most ", d / nc, " rank(s) with the rows split evenly, ") : std::string(),
               "or fewer columns per step (a smaller maxRank or block size)");
  ++steps_.tsqr;
  Teuchos::SerialDenseMatrix<int, double> R(nc, nc);
  MultiVector Q(map_, nc);
  Tpetra::TsqrAdaptor<MultiVector> tsqr;
  tsqr.factorExplicit(Y, Q, R);
  // R = W S Z^T: only W and S are needed (LAPACK, replicated: R is the same on every rank).
  std::vector<double> S(nc), W(static_cast<size_t>(nc) * nc);
  denseLeftSvd(nc, nc, R.values(), R.stride(), S, W);
  const int keep = truncate(S, nc);
  auto local = rcp(new Map(nc, 0, map_->getComm(), Tpetra::LocallyReplicated));
  MultiVector Wk(local, std::max(keep, 1));
  {
    auto w = Wk.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (int j = 0; j < keep; ++j)
      for (int a = 0; a < nc; ++a) w(a, j) = W[a + static_cast<size_t>(nc) * j];
  }
  U_ = rcp(new MultiVector(map_, std::max(keep, 1)));
  if (keep > 0) U_->multiply(Teuchos::NO_TRANS, Teuchos::NO_TRANS, 1.0, Q, Wk, 0.0);
}

void StreamingPod::step(const MultiVector& X, size_t c0, size_t c1) {
  const int nc = rank() + static_cast<int>(c1 - c0);
  switch (stepRoute(route_, map_->getComm()->getSize())) {
    case PodRoute::Stacked:
      ++steps_.stacked;
      return stackedStep(leafColumns(X, c0, c1), nc);
    case PodRoute::Tree:
      ++steps_.tree;
      return treeStep(leafColumns(X, c0, c1), nc);
    case PodRoute::Replicated:
      ++steps_.replicated;
      return replicatedStep(stepMatrix(X, c0, c1));
    default: {  // PodRoute::Tsqr (stepRoute resolves Auto)
      MultiVector Y = stepMatrix(X, c0, c1);
      return tsqrStep(Y);
    }
  }
}

}  // namespace gphr
