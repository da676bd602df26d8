#include "gphr/reduction/Deim.hpp"

#include <Teuchos_BLAS.hpp>
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_LAPACK.hpp>
#include <Teuchos_OrdinalTraits.hpp>

#include <cmath>
#include <limits>
#include <memory>

#include "gphr/core/Error.hpp"
#include "gphr/core/ReplicatedGather.hpp"

namespace gphr {

namespace {
using Lapack = Teuchos::LAPACK<int, double>;

// Solve B x = rhs (B m x m column-major, overwritten by its LU) or B^T x = rhs.
void luSolve(std::vector<double>& B, int m, std::vector<double>& rhs, char trans, const char* what) {
  Lapack lapack;
  std::vector<int> piv(m);
  int info = 0;
  lapack.GETRF(m, m, B.data(), m, piv.data(), &info);
  GPHR_REQUIRE(info == 0, InputError, what, ": P^T U is singular (LAPACK GETRF info = ", info,
               "): the DEIM basis is rank-deficient at the sampled rows");
  lapack.GETRS(trans, m, 1, B.data(), m, piv.data(), rhs.data(), m, &info);
}

// Greedy DEIM (Chaturantabut & Sorensen, Alg. 1) as Gaussian elimination with partial (row)
// pivoting on U: after l elimination steps, column l of the Schur complement is exactly the DEIM
// residual u_l - U_l (P^T U_l)^{-1} P^T u_l, and the next index is its largest entry (Sorensen &
// Embree 2016). The elimination is LAPACK GETRF's right-looking blocked LU, written out here
// because the pivot search is global: each index costs one collective (every rank offers its best
// row with the row itself, so the pivot row arrives with the argmax). Inside a panel of
// kGreedyPanel columns only the panel is updated (axpys); the columns to its right get the
// panel's whole update at once, U12 = L11^{-1} A12 (TRSM) and A22 -= L21 U12 (GEMM), so most of
// the d m^2 / 2 flops run at BLAS-3 speed (paper-size run, d = 2048, m = 100: 5.5 -> 2.9 ms per
// call against the row-by-row elimination). Ties go to the smallest gid. Each row's arithmetic
// is the same on any rank count (a GEMM row depends only on its own row of L21, and its 32-term
// inner products are not split), so the indices are too.
constexpr int kGreedyPanel = 32;

// This rank's offer for DEIM index l in the panel starting at column l0: |pivot| of its largest
// untaken entry of residual column l (-1: none), its gid (exact below 2^53), then that row's
// entries l0..m-1 (the pivot row's, should it win). Ties go to the smallest gid. W: this rank's
// rows of the columns, column-major with leading dimension ld.
void offerPivot(const double* W, LO ld, const std::vector<char>& taken, const std::vector<GO>& gid, bool increasingGids,
                int l, int l0, int m, std::vector<double>& offer) {
  const double* c = W + static_cast<size_t>(ld) * l;
  const LO nl = static_cast<LO>(gid.size());
  // The largest |c_i| over the untaken rows in four independent lanes, each keeping its first
  // row at its maximum, without a branch (the tie rule inside the scan kept it from pipelining;
  // with the division below, the selection's own CPU time on the paper's GP-ADEIM run fell by a
  // third, perf samples 296 -> 201 over 601 selections). Where gids
  // grow with the local index (a contiguous map) a lane's first row is its smallest gid, and the
  // lanes are compared by the tie rule; otherwise a second scan finds the smallest gid at the
  // maximum. Either way the row of the one-pass rule; a NaN entry is never taken.
  double m4[4] = {-1.0, -1.0, -1.0, -1.0};
  LO i4[4] = {-1, -1, -1, -1}, i = 0;
  for (; i + 4 <= nl; i += 4)
    for (int q = 0; q < 4; ++q) {
      const double a = taken[i + q] ? -1.0 : std::abs(c[i + q]);
      const bool more = a > m4[q];
      m4[q] = more ? a : m4[q];
      i4[q] = more ? i + q : i4[q];
    }
  for (; i < nl; ++i) {
    const double a = taken[i] ? -1.0 : std::abs(c[i]);
    if (a > m4[0]) m4[0] = a, i4[0] = i;  // after lane 0's rows: its first row at the maximum kept
  }
  LO best = -1;
  double bestAbs = -1.0;
  for (int q = 0; q < 4; ++q)
    if (i4[q] >= 0 && (best < 0 || m4[q] > bestAbs || (m4[q] == bestAbs && gid[i4[q]] < gid[best])))
      best = i4[q], bestAbs = m4[q];
  if (!increasingGids && best >= 0)
    for (LO r = 0; r < nl; ++r)
      if (!taken[r] && std::abs(c[r]) == bestAbs && gid[r] < gid[best]) best = r;
  std::fill(offer.begin(), offer.end(), 0.0);
  offer[0] = -1.0;
  if (best < 0) return;
  offer[0] = bestAbs;
  offer[1] = static_cast<double>(gid[best]);
  for (int j = l0; j < m; ++j) offer[2 + j - l0] = W[best + static_cast<size_t>(ld) * j];
}

// The winning rank among the gathered offers (np of `width` entries each): the largest |pivot|,
// ties to the smallest gid; -1 when no rank offered a row.
int winningOffer(const std::vector<double>& all, int np, int width) {
  int win = -1;
  for (int p = 0; p < np; ++p) {
    const double* o = &all[static_cast<size_t>(p) * width];
    if (o[0] < 0.0) continue;
    const double* w = win < 0 ? nullptr : &all[static_cast<size_t>(win) * width];
    if (!w || o[0] > w[0] || (o[0] == w[0] && o[1] < w[1])) win = p;
  }
  return win;
}

// The panel [l0, l1)'s whole update of the columns to its right (GETRF's trailing update):
// U12 = L11^{-1} A12 (L11 unit lower triangular, from the panel's pivot rows, row-major of `width`
// entries), then A22 -= L21 U12 on every row (the taken rows' multipliers are zero). W: this rank's
// nl rows of the columns, column-major with leading dimension ld.
void trailingUpdate(const std::vector<double>& panelRows, int width, int l0, int l1, int m, double* W, LO nl, LO ld) {
  Teuchos::BLAS<int, double> blas;
  const int nb = l1 - l0, nt = m - l1;
  std::vector<double> L11(static_cast<size_t>(nb) * nb, 0.0), U12(static_cast<size_t>(nb) * nt);
  for (int a = 0; a < nb; ++a) {
    const double* row = &panelRows[static_cast<size_t>(a) * width];
    for (int b = 0; b < a; ++b) L11[a + static_cast<size_t>(nb) * b] = row[b];
    for (int j = 0; j < nt; ++j) U12[a + static_cast<size_t>(nb) * j] = row[nb + j];
  }
  blas.TRSM(Teuchos::LEFT_SIDE, Teuchos::LOWER_TRI, Teuchos::NO_TRANS, Teuchos::UNIT_DIAG, nb, nt, 1.0, L11.data(), nb,
            U12.data(), nb);
  if (nl > 0)
    blas.GEMM(Teuchos::NO_TRANS, Teuchos::NO_TRANS, nl, nt, nb, -1.0, W + static_cast<size_t>(ld) * l0, ld, U12.data(),
              nb, 1.0, W + static_cast<size_t>(ld) * l1, ld);
}

std::vector<GO> greedyDeim(const MultiVector& U, int m) {
  const Map& map = *U.getMap();
  const LO nl = static_cast<LO>(map.getNodeNumElements());
  const int np = map.getComm()->getSize(), ld = std::max<LO>(nl, 1);
  // This rank's rows of U, column-major; every entry is copied in below, so not zero-filled.
  const std::unique_ptr<double[]> Wbuf(new double[static_cast<size_t>(ld) * m]);
  double* W = Wbuf.get();
  std::vector<GO> gid(nl);
  {
    auto u = U.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (int j = 0; j < m; ++j)
      for (LO i = 0; i < nl; ++i) W[i + static_cast<size_t>(ld) * j] = u(i, j);
    for (LO i = 0; i < nl; ++i) gid[i] = map.getGlobalElement(i);
  }
  bool increasing = true;  // gids grow with the local index (offerPivot's single scan)
  for (LO i = 1; i < nl; ++i) increasing = increasing && gid[i] > gid[i - 1];
  auto col = [&](int j) { return W + static_cast<size_t>(ld) * j; };
  std::vector<double> colMax(m, 0.0), globalMax(m, 0.0);  // max_i |U(i, l)|: the scale of column l's residual
  for (int j = 0; j < m; ++j)
    for (LO i = 0; i < nl; ++i) colMax[j] = std::max(colMax[j], std::abs(col(j)[i]));
  Teuchos::reduceAll(*map.getComm(), Teuchos::REDUCE_MAX, m, colMax.data(), globalMax.data());
  Teuchos::BLAS<int, double> blas;
  std::vector<char> taken(nl, 0);
  std::vector<LO> takenRows;  // the local rows taken so far (at most m)
  takenRows.reserve(m);
  std::vector<double> offer(m + 2), all(static_cast<size_t>(np) * (m + 2));
  std::vector<double> panelRows(static_cast<size_t>(kGreedyPanel) * m);  // the panel's pivot rows, row-major
  std::vector<GO> idx;
  for (int l0 = 0; l0 < m; l0 += kGreedyPanel) {
    const int l1 = std::min(m, l0 + kGreedyPanel), width = m - l0;
    for (int l = l0; l < l1; ++l) {
      offerPivot(W, ld, taken, gid, increasing, l, l0, m, offer);
      Teuchos::gatherAll(*map.getComm(), m + 2, offer.data(), static_cast<int>(all.size()), all.data());
      const int win = winningOffer(all, np, m + 2);
      const double* pivot = &all[static_cast<size_t>(std::max(win, 0)) * (m + 2)];
      // A residual at the round-off level of its column (d eps relative) is a dependent column.
      const double floor = 10.0 * static_cast<double>(map.getGlobalNumElements()) *
                           std::numeric_limits<double>::epsilon() * globalMax[l];
      GPHR_REQUIRE(win >= 0 && pivot[0] > floor && std::isfinite(pivot[0]), InputError,
                   "greedy DEIM: the residual of DEIM basis column ", l + 1, " vanishes (", win < 0 ? 0.0 : pivot[0],
                   " against max |u| = ", globalMax[l], "): the DEIM basis is rank-deficient; use m <= ", l);
      const GO g = static_cast<GO>(pivot[1]);
      idx.push_back(g);
      const LO mine = map.getLocalElement(g);
      if (mine != Teuchos::OrdinalTraits<LO>::invalid()) taken[mine] = 1, takenRows.push_back(mine);
      // Row l - l0 of [L11 U11 | A12]: multipliers left of l, the pivot, the panel's updated
      // entries, then the trailing entries as they stood when the panel began.
      const double* p = pivot + 2;
      std::copy_n(p, width, panelRows.begin() + static_cast<size_t>(l - l0) * width);
      // Multipliers L21 = column l / pivot in place (zero on taken rows, which then never change),
      // and the panel's columns right of l updated by them.
      double* f = col(l);
      // (every row divided, then the taken rows zeroed: a loop without a branch, which vectorizes;
      // with the branch inside, the divisions ran one by one)
      const double pivotValue = p[l - l0];
      for (LO i = 0; i < nl; ++i) f[i] /= pivotValue;
      for (LO t : takenRows) f[t] = 0.0;
      for (int j = l + 1; j < l1; ++j) blas.AXPY(nl, -p[j - l0], f, 1, col(j), 1);
    }
    if (l1 < m) trailingUpdate(panelRows, width, l0, l1, m, W, nl, ld);
  }
  return idx;
}

}  // namespace

std::pair<GO, double> globalArgmaxAbs(const Map& map, const std::vector<double>& x, const std::vector<char>& exclude) {
  double best[2] = {-1.0, -1.0};  // |x|, gid (exact in a double below 2^53)
  for (LO i = 0; i < static_cast<LO>(map.getNodeNumElements()); ++i) {
    if (exclude[i]) continue;
    const double a = std::abs(x[i]), g = static_cast<double>(map.getGlobalElement(i));
    if (a > best[0] || (a == best[0] && g < best[1])) best[0] = a, best[1] = g;
  }
  const int np = map.getComm()->getSize();
  std::vector<double> all(2 * static_cast<size_t>(np));
  Teuchos::gatherAll(*map.getComm(), 2, best, 2 * np, all.data());
  std::pair<GO, double> out{-1, -1.0};
  for (int p = 0; p < np; ++p) {
    const double v = all[2 * p], g = all[2 * p + 1];
    if (g >= 0.0 && (v > out.second || (v == out.second && static_cast<GO>(g) < out.first))) out = {static_cast<GO>(g), v};
  }
  return out;
}

std::vector<GO> replaceDeimIndices(const MultiVector& U, std::vector<GO> P, const std::vector<int>& columns) {
  const Map& map = *U.getMap();
  const int m = static_cast<int>(P.size()), nc = static_cast<int>(U.getNumVectors());
  GPHR_REQUIRE(m >= 1 && m <= nc, InputError, "DEIM point update: ", m, " indices for a basis of ", nc, " columns");
  const LO nl = static_cast<LO>(map.getNodeNumElements());
  auto u = U.getLocalViewHost(Tpetra::Access::ReadOnly);
  std::vector<double> res(nl);
  for (int i : columns) {
    GPHR_REQUIRE(i >= 0 && i < m, InputError, "DEIM point update: column ", i, " is not one of 0 to ", m - 1);
    const std::vector<double> rows = gatherRows(U, P);  // (P^T U)(a, b) = rows[a * nc + b]
    const int k = m - 1;
    std::vector<double> B(static_cast<size_t>(k) * k), c(k);
    for (int a = 0, ra = 0; a < m; ++a) {
      if (a == i) continue;
      c[ra] = rows[static_cast<size_t>(a) * nc + i];
      for (int b = 0, cb = 0; b < m; ++b)
        if (b != i) B[ra + static_cast<size_t>(k) * cb++] = rows[static_cast<size_t>(a) * nc + b];
      ++ra;
    }
    if (k > 0) luSolve(B, k, c, 'N', "DEIM point update");
    std::vector<char> exclude(nl, 0);
    for (int a = 0; a < m; ++a) {
      const LO l = map.getLocalElement(P[a]);
      if (a != i && l != Teuchos::OrdinalTraits<LO>::invalid()) exclude[l] = 1;
    }
    for (LO l = 0; l < nl; ++l) res[l] = u(l, i);
    for (int b = 0, cb = 0; b < m; ++b) {  // column by column: U is column-major (LayoutLeft)
      if (b == i) continue;
      const double cj = c[cb++];
      for (LO l = 0; l < nl; ++l) res[l] -= u(l, b) * cj;
    }
    const auto [gid, val] = globalArgmaxAbs(map, res, exclude);
    GPHR_REQUIRE(gid >= 0 && val > 0.0 && std::isfinite(val), InputError, "DEIM point update: the residual of column ",
                 i + 1, " against the other ", k, " vanishes (", val, ")");
    P[i] = gid;
  }
  return P;
}

namespace {

std::vector<GO> qdeim(const MultiVector& U, int m) {
  const Map& map = *U.getMap();
  const GO d = static_cast<GO>(map.getGlobalNumElements());
  std::vector<GO> all(d);
  for (GO i = 0; i < d; ++i) all[i] = map.getMinAllGlobalIndex() + i;
  GPHR_REQUIRE(map.getMaxAllGlobalIndex() - map.getMinAllGlobalIndex() + 1 == d, InputError,
               "QDEIM needs a row map of G with global ids without gaps");
  const int nc = static_cast<int>(U.getNumVectors());
  const std::vector<double> rows = gatherRows(U, all);  // d x nc row-major = U^T column-major (nc x d)
  std::vector<double> Ut(static_cast<size_t>(m) * d);
  for (GO i = 0; i < d; ++i)
    for (int j = 0; j < m; ++j) Ut[j + static_cast<size_t>(m) * i] = rows[static_cast<size_t>(i) * nc + j];
  std::vector<int> jpvt(d, 0);
  std::vector<double> tau(std::min<GO>(m, d)), work(1);
  int info = 0;
  Lapack lapack;
  lapack.GEQP3(m, static_cast<int>(d), Ut.data(), m, jpvt.data(), tau.data(), work.data(), -1, nullptr, &info);
  work.resize(std::max(1, static_cast<int>(work[0])));
  lapack.GEQP3(m, static_cast<int>(d), Ut.data(), m, jpvt.data(), tau.data(), work.data(),
               static_cast<int>(work.size()), nullptr, &info);
  GPHR_REQUIRE(info == 0, SolverError, "QDEIM: LAPACK GEQP3 failed (info = ", info, ")");
  std::vector<GO> idx(m);
  for (int j = 0; j < m; ++j) idx[j] = all[jpvt[j] - 1];
  return idx;
}
// P^T U (m x m, column-major) from the gathered rows (row-major, nc entries each).
std::vector<double> pointRows(const std::vector<double>& rows, int m, int nc) {
  std::vector<double> B(static_cast<size_t>(m) * m);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) B[i + static_cast<size_t>(m) * j] = rows[static_cast<size_t>(i) * nc + j];
  return B;
}

// cond_2 from the singular values (m is small: a dense LAPACK SVD is the right tool).
double conditionNumber(std::vector<double> B, int m) {
  std::vector<double> S(m), work(1), dummy(1);
  int info = 0;
  Lapack lapack;
  lapack.GESVD('N', 'N', m, m, B.data(), m, S.data(), dummy.data(), 1, dummy.data(), 1, work.data(), -1, nullptr, &info);
  work.resize(std::max(1, static_cast<int>(work[0])));
  lapack.GESVD('N', 'N', m, m, B.data(), m, S.data(), dummy.data(), 1, dummy.data(), 1, work.data(),
               static_cast<int>(work.size()), nullptr, &info);
  return S[m - 1] > 0.0 ? S[0] / S[m - 1] : std::numeric_limits<double>::infinity();
}
}  // namespace

double deimConditionNumber(const MultiVector& U, const std::vector<GO>& indices) {
  const int m = static_cast<int>(indices.size()), nc = static_cast<int>(U.getNumVectors());
  GPHR_REQUIRE(m >= 1 && m <= nc, InputError, "DEIM: ", m, " indices for a basis of ", nc, " columns");
  return conditionNumber(pointRows(gatherRows(U, indices), m, nc), m);
}

std::vector<GO> selectDeimIndices(const MultiVector& U, int m, const std::string& method) {
  GPHR_REQUIRE(m >= 1 && m <= static_cast<int>(U.getNumVectors()), InputError, "DEIM: m = ", m,
               " is not available: the DEIM basis has ", U.getNumVectors(), " columns (allowed: 1 to ",
               U.getNumVectors(), ")");
  GPHR_REQUIRE(m <= static_cast<GO>(U.getGlobalLength()), InputError, "DEIM: m = ", m, " exceeds d = ",
               U.getGlobalLength());
  if (method == "deim") return greedyDeim(U, m);
  GPHR_REQUIRE(method == "qdeim", InputError, "DEIM index method '", method, "' is not one of 'deim', 'qdeim'");
  return qdeim(U, m);
}

DeimWeights computeDeimWeights(const MultiVector& U, const std::vector<GO>& indices, const Vector& v,
                               bool estimateCondition) {
  const int m = static_cast<int>(indices.size()), nc = static_cast<int>(U.getNumVectors());
  GPHR_REQUIRE(m >= 1 && m <= nc, InputError, "DEIM weights: ", m, " indices for a basis of ", nc, " columns");
  auto local = rcp(new Map(nc, 0, U.getMap()->getComm(), Tpetra::LocallyReplicated));
  MultiVector Utv(local, 1);
  Utv.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, U, v, 0.0);
  const std::vector<double> rows = gatherRows(U, indices);  // (P^T U)(i, j) = rows[i * nc + j]
  std::vector<double> B = pointRows(rows, m, nc);
  DeimWeights out;
  out.pointRows = B;
  double norm1 = 0.0;  // ||B||_1 before the LU overwrites B: the max column sum (Teuchos::LAPACK has no LANGE)
  for (int j = 0; j < m && estimateCondition; ++j) {
    double col = 0.0;
    for (int i = 0; i < m; ++i) col += std::abs(B[i + static_cast<size_t>(m) * j]);
    norm1 = std::max(norm1, col);
  }
  if (!estimateCondition) out.conditionNumber = conditionNumber(B, m);
  out.weights.resize(m);
  auto c = Utv.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (int j = 0; j < m; ++j) out.weights[j] = c(j, 0);
  luSolve(B, m, out.weights, 'T', "DEIM weights");  // (P^T U)^T x = U^T v; B now holds the LU
  if (estimateCondition) {
    Lapack lapack;
    double rcond = 0.0;
    std::vector<double> work(4 * m);
    std::vector<int> iwork(m);
    int info = 0;
    lapack.GECON('1', m, B.data(), m, norm1, &rcond, work.data(), iwork.data(), &info);
    out.conditionNumber = rcond > 0.0 ? 1.0 / rcond : std::numeric_limits<double>::infinity();
  }
  return out;
}

}  // namespace gphr
