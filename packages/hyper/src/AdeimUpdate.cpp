#include "gphr/hyper/AdeimUpdate.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_LAPACK.hpp>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "gphr/core/Error.hpp"
#include "gphr/reduction/DenseQr.hpp"
#include "gphr/reduction/DenseSvd.hpp"

namespace gphr {
namespace {

using Teuchos::NO_TRANS;
using Teuchos::TRANS;

// Thin SVD A = U diag(s) Vt of a small dense matrix by GESDD (denseThinSvd); an update takes the
// values of M's R factor and of the tau_r test's matrix, and R's vectors only when r < r_C.
// withVectors = false: the values only.
struct ThinSvd {
  DenseMatrix U, Vt;
  std::vector<double> s;
};

ThinSvd thinSvd(const DenseMatrix& A, bool withVectors = true) {
  const int m = A.numRows(), n = A.numCols(), mn = std::min(m, n);
  ThinSvd r;
  r.s.assign(mn, 0.0);
  if (withVectors) {
    r.U.shape(m, mn);
    r.Vt.shape(mn, n);
  }
  if (mn == 0) return r;
  DenseMatrix a(A);
  denseThinSvd(m, n, a.values(), a.stride(), r.s.data(), withVectors ? r.U.values() : nullptr, r.U.stride(),
               withVectors ? r.Vt.values() : nullptr, r.Vt.stride(), withVectors, "GP-ADEIM");
  return r;
}

// The R factor of a tall m x n matrix (m > n; GEQRT, blocked: denseQrFactorR): the same
// singular values and right singular vectors, and the SVD of the n x n R is what the update
// needs (its left vectors are not: a_i = -M w_i is one GEMM). At 250 x 100, the QR + GESDD of R
// take 2.3 ms against 3.1 ms for GESDD of the whole matrix (one thread, CPU time, with GEQRF).
// Wide or square matrices are returned as they are.
DenseMatrix rFactor(const DenseMatrix& A) {
  const int m = A.numRows(), n = A.numCols();
  if (m <= n || n == 0) return A;
  DenseMatrix a(A), R(n, n);
  denseQrFactorR(m, n, a.values(), a.stride(), R.values(), R.stride(), "GP-ADEIM");
  return R;
}

// Singular values above tol * s_1 (and above zero).
int countAbove(const std::vector<double>& s, double tol) {
  int r = 0;
  while (r < static_cast<int>(s.size()) && s[r] > 0.0 && s[r] > tol * s[0]) ++r;
  return r;
}

bool allFinite(const DenseMatrix& A) {
  for (int j = 0; j < A.numCols(); ++j)
    for (int i = 0; i < A.numRows(); ++i)
      if (!std::isfinite(A(i, j))) return false;
  return true;
}

// op(A) op(B); C is not zero-filled first (GEMM with beta = 0 overwrites it).
DenseMatrix product(Teuchos::ETransp ta, Teuchos::ETransp tb, const DenseMatrix& A, const DenseMatrix& B) {
  DenseMatrix C(ta == NO_TRANS ? A.numRows() : A.numCols(), tb == NO_TRANS ? B.numCols() : B.numRows(), false);
  C.multiply(ta, tb, 1.0, A, B, 0.0);
  return C;
}

}  // namespace

// (P^T U)^{-1} by GETRF + GETRI, then one GEMM: OpenBLAS's triangular solves with 400 right-hand
// sides (GESV) took 1.2 ms at m = 100 against 0.56 ms for this (one thread, CPU time). Both have
// forward errors of order cond(P^T U) eps, and cond(P^T U) is what the report monitors.
DenseMatrix deimCoefficients(const DenseMatrix& PtU, const DenseMatrix& PtF) {
  const int m = PtU.numRows();
  GPHR_REQUIRE(PtU.numCols() == m && PtF.numRows() == m, InputError, "DEIM coefficients: P^T U is ", m, " x ",
               PtU.numCols(), " and P^T F has ", PtF.numRows(), " rows (need m x m and m rows)");
  DenseMatrix inv(PtU);
  std::vector<int> piv(m);
  int info = 0;
  Teuchos::LAPACK<int, double> lapack;
  lapack.GETRF(m, m, inv.values(), inv.stride(), piv.data(), &info);
  if (info == 0) {
    double query = 0.0;
    lapack.GETRI(m, inv.values(), inv.stride(), piv.data(), &query, -1, &info);
    std::vector<double> work(std::max(1, static_cast<int>(query)));
    lapack.GETRI(m, inv.values(), inv.stride(), piv.data(), work.data(), static_cast<int>(work.size()), &info);
  }
  GPHR_REQUIRE(info == 0 && allFinite(inv), InputError,
               "DEIM coefficients: P^T U is singular (LAPACK GETRF/GETRI info = ", info,
               "): the interpolation rows do not determine the DEIM basis");
  return product(NO_TRANS, NO_TRANS, inv, PtF);
}

namespace {
// X <- H_1 ... H_k X: the first k Householder reflectors of a GEQRF or GEQP3 factor QR applied from
// the left (ORMQR after its workspace query).
void applyReflectors(const DenseMatrix& QR, int k, const std::vector<double>& tau, DenseMatrix& X) {
  Teuchos::LAPACK<int, double> lapack;
  std::vector<double> work(1);
  int info = 0;
  lapack.ORMQR('L', 'N', X.numRows(), X.numCols(), k, QR.values(), QR.stride(), tau.data(), X.values(), X.stride(),
               work.data(), -1, &info);
  work.resize(std::max<size_t>(1, static_cast<size_t>(work[0])));
  lapack.ORMQR('L', 'N', X.numRows(), X.numCols(), k, QR.values(), QR.stride(), tau.data(), X.values(), X.stride(),
               work.data(), static_cast<int>(work.size()), &info);
  GPHR_REQUIRE(info == 0, SolverError, "GP-ADEIM: LAPACK ORMQR (", X.numRows(), " x ", X.numCols(), ") failed, info = ",
               info);
}

// T^+ = T^T (T T^T)^{-1} of T = [R11 R12] Pi^T (r_C x m, full row rank r_C; Ct holds R11 R12 in
// its upper triangle, jpvt is Pi): the minimum-norm right inverse. Its columns span range(T^T) =
// range(C) (C ~ T^T Q_1^T), so b = T^+ w is the b of least norm with T b = w, the paper's
// b = Q_j z after theo:minprob_eig_equivalence. Any other right inverse, such as
// Pi [R11^{-1}; 0] when R12 != 0, adds to b a part in null(C^T): the objective of eq:min_prob does
// not see it, but U_{j+1} turns in directions no data asked for. With r_C = m (no R12), T is square
// and T^+ = T^{-1} = Pi R11^{-1} (one TRTRI); otherwise from the thin QR T^T = Q_T R_T (GEQRF):
// T^+ = Q_T R_T^{-T} (TRTRI, then ORMQR applies Q_T), never forming the Gram matrix T T^T.
DenseMatrix pseudoInverse(const DenseMatrix& T, const DenseMatrix& Ct, const std::vector<int>& jpvt) {
  const int rc = T.numRows(), m = T.numCols();
  DenseMatrix Tplus(m, rc);
  if (rc == 0) return Tplus;
  const bool square = rc == m;
  DenseMatrix QR(m, rc, false), Rinv(rc, rc);
  for (int j = 0; j < rc; ++j)
    for (int i = 0; i < m; ++i) QR(i, j) = T(j, i);
  std::vector<double> tau(rc), work(1);
  int info = 0;
  Teuchos::LAPACK<int, double> lapack;
  if (!square) {
    lapack.GEQRF(m, rc, QR.values(), QR.stride(), tau.data(), work.data(), -1, &info);
    work.resize(std::max<size_t>(1, static_cast<size_t>(work[0])));
    lapack.GEQRF(m, rc, QR.values(), QR.stride(), tau.data(), work.data(), static_cast<int>(work.size()), &info);
    GPHR_REQUIRE(info == 0, SolverError, "GP-ADEIM: LAPACK GEQRF of T^T (", m, " x ", rc, ") failed, info = ", info);
  }
  const DenseMatrix& R = square ? Ct : QR;  // R11 (of C^T's pivoted QR) or R_T
  for (int j = 0; j < rc; ++j)
    for (int i = 0; i <= j; ++i) Rinv(i, j) = R(i, j);
  lapack.TRTRI('U', 'N', rc, Rinv.values(), Rinv.stride(), &info);
  GPHR_REQUIRE(info == 0, SolverError, "GP-ADEIM: LAPACK TRTRI of the kept triangular factor failed, info = ", info);
  if (square) {
    for (int i = 0; i < rc; ++i)
      for (int l = 0; l < rc; ++l) Tplus(jpvt[i] - 1, l) = Rinv(i, l);
    return Tplus;
  }
  for (int j = 0; j < rc; ++j)
    for (int i = j; i < rc; ++i) Tplus(i, j) = Rinv(j, i);  // [R_T^{-T}; 0]
  applyReflectors(QR, rc, tau, Tplus);
  return Tplus;
}
}  // namespace

// C^T Pi = Q R by LAPACK GEQP3 (Householder QR with column pivoting, |R_11| >= |R_22| >= ...):
// the rank-revealing factorization the paper prescribes after theo:minprob_eig_equivalence, on
// the tall C^T so that Q spans C's row space, where C^T b lives. Cut where |R_ll| <= tol |R_11|:
// C^T ~ Q_1 [R11 R12] Pi^T = Q_1 T. At 400 x 100 (the paper's benchmark) GEQP3 + ORGQR took
// 2.0 ms against GESDD's 4.7 ms for the thin SVD this replaced (one thread, CPU time); every use
// below needs only an orthonormal basis of the row space and T, not singular vectors.
CoefficientFactor factorCoefficients(const DenseMatrix& PtU, const DenseMatrix& PtF, double tol) {
  GPHR_REQUIRE(tol >= 0.0, InputError, "GP-ADEIM: coefficientTol = ", tol, " (need >= 0)");
  return factorCoefficients(deimCoefficients(PtU, PtF), tol);
}

CoefficientFactor factorCoefficients(DenseMatrix C, double tol) {
  GPHR_REQUIRE(tol >= 0.0, InputError, "GP-ADEIM: coefficientTol = ", tol, " (need >= 0)");
  CoefficientFactor f;
  f.C = std::move(C);
  const int m = f.C.numRows(), wbar = f.C.numCols(), k = std::min(m, wbar);
  DenseMatrix Ct(wbar, m, false);  // every entry written below
  for (int j = 0; j < wbar; ++j)
    for (int i = 0; i < m; ++i) Ct(j, i) = f.C(i, j);
  std::vector<int> jpvt(m, 0);
  std::vector<double> tau(std::max(k, 1)), work(1);
  int info = 0, rc = 0;
  Teuchos::LAPACK<int, double> lapack;
  if (k > 0) {
    lapack.GEQP3(wbar, m, Ct.values(), Ct.stride(), jpvt.data(), tau.data(), work.data(), -1, nullptr, &info);
    work.resize(std::max<size_t>(1, static_cast<size_t>(work[0])));
    lapack.GEQP3(wbar, m, Ct.values(), Ct.stride(), jpvt.data(), tau.data(), work.data(), static_cast<int>(work.size()),
                 nullptr, &info);
    GPHR_REQUIRE(info == 0, SolverError, "GP-ADEIM: LAPACK GEQP3 of C^T (", wbar, " x ", m, ") failed, info = ", info);
    const double r11 = std::abs(Ct(0, 0));
    while (rc < k && std::abs(Ct(rc, rc)) > 0.0 && std::abs(Ct(rc, rc)) > tol * r11) ++rc;
  }
  // T = [R11 R12] Pi^T (r_C x m) and its pseudo-inverse T^+ (m x r_C).
  f.T.shape(rc, m);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < std::min(rc, j + 1); ++i) f.T(i, jpvt[j] - 1) = Ct(i, j);
  f.Tinv = pseudoInverse(f.T, Ct, jpvt);
  if (rc > 0) {
    // Q_1 = H_1 ... H_rc [I; 0] by ORMQR, not ORGQR: below its crossover (128 columns) ORGQR runs
    // the unblocked DORG2R, while ORMQR applies the reflectors in blocks (0.69 against 0.88 ms at
    // 400 x 100, one thread).
    f.Q.shape(wbar, rc);
    for (int l = 0; l < rc; ++l) f.Q(l, l) = 1.0;
    applyReflectors(Ct, rc, tau, f.Q);
  } else {
    f.Q.shape(wbar, 0);
  }
  f.cut = rc < k;
  return f;
}

// eq:gen_eval is solved through the factor of C instead of LAPACK's SYGV on the pencil: with
// C^T ~ Q_1 T (rank r_C after the cut-off) and y = T b, ||C^T b|| = ||y|| and S^T R C^T b =
// M y with M = X Q_1 (m_s x r_C), X = S^T R. The pencil (C X^T X C^T, C C^T) becomes the standard
// symmetric eigenproblem of M^T M: lambda_i = sigma_i(M)^2, and b_i = T^+ w_i is the solution of
// T b_i = w_i of least norm, w_i the right singular vectors of M (GESDD): of all b with the same
// C^T b (the same objective of eq:min_prob), the one in range(C), as in the paper's b_i = Q_j z_i. This never forms C C^T, whose condition number is
// cond(C)^2. (The tests check the result against SYGV on well-conditioned data.)
AdeimUpdate computeAdeimUpdate(const DenseMatrix& PtU, const DenseMatrix& PtF, const DenseMatrix& StU,
                               const DenseMatrix& StF, const AdeimUpdateOptions& opt) {
  return computeAdeimUpdate(factorCoefficients(PtU, PtF, opt.coefficientTol), StU, StF, opt);
}

AdeimUpdate computeAdeimUpdate(const CoefficientFactor& cf, const DenseMatrix& StU, const DenseMatrix& StF,
                               const AdeimUpdateOptions& opt) {
  SampledRowShare all;
  all.numRows = StU.numRows();
  all.positions.resize(all.numRows);
  for (int i = 0; i < all.numRows; ++i) all.positions[i] = i;
  return computeAdeimUpdate(cf, StU, StF, opt, all);
}

namespace {
// One rank's failure inside work that only some ranks do, re-thrown on every rank after the
// reduction that would otherwise wait for it.
void throwIfFailed(double failed, const std::string& what) {
  GPHR_REQUIRE(failed == 0.0, SolverError,
               "GP-ADEIM update: ", what.empty() ? "a LAPACK call failed on another rank" : what);
}

void sumAll(const SampledRowShare& share, std::vector<double>& buf) {
  if (share.comm.is_null() || share.comm->getSize() == 1 || buf.empty()) return;
  std::vector<double> in(buf);
  Teuchos::reduceAll(*share.comm, Teuchos::REDUCE_SUM, static_cast<int>(buf.size()), in.data(), buf.data());
}

// Rows of a replicated m_s x cols matrix scattered from this rank's rows (zero elsewhere) into buf
// at offset, column-major: the sum over ranks assembles it (each row comes from one rank).
void scatterOwnRows(const DenseMatrix& own, const SampledRowShare& share, std::vector<double>& buf, size_t offset) {
  for (int c = 0; c < own.numCols(); ++c)
    for (int i = 0; i < own.numRows(); ++i)
      buf[offset + static_cast<size_t>(c) * share.numRows + share.positions[i]] = own(i, c);
}

DenseMatrix columnMajor(const std::vector<double>& buf, size_t offset, int rows, int cols) {
  DenseMatrix M(rows, cols);
  for (int c = 0; c < cols; ++c)
    for (int i = 0; i < rows; ++i) M(i, c) = buf[offset + static_cast<size_t>(c) * rows + i];
  return M;
}

// The singular values of R and, when Z is given, the number of Z's singular values above
// tol s_1(Z), values only (GESDD without vectors: 0.85 ms at 100 x 100 against 2.3 ms with them,
// one thread): independent, so with two or more ranks the first rank computes the one and the
// last rank the other at the same time, and one sum-reduction hands both to every rank. The same
// calls on the same replicated data as on one rank, so the same numbers on any rank count.
void splitSingularValues(const SampledRowShare& share, const DenseMatrix& R, const DenseMatrix* Z, double tol,
                         std::vector<double>& s, int& count) {
  const int np = share.comm.is_null() ? 1 : share.comm->getSize();
  if (np == 1 || Z == nullptr) {
    s = thinSvd(R, false).s;
    count = Z ? countAbove(thinSvd(*Z, false).s, tol) : 0;
    return;
  }
  const int me = share.comm->getRank(), k = std::min(R.numRows(), R.numCols());
  std::vector<double> buf(k + 2, 0.0);
  std::string error;
  try {
    if (me == 0) {
      const std::vector<double> mine = thinSvd(R, false).s;
      std::copy(mine.begin(), mine.end(), buf.begin());
    }
    if (me == np - 1) buf[k] = countAbove(thinSvd(*Z, false).s, tol);
  } catch (const std::exception& e) {
    error = e.what();
    buf.back() = 1.0;
  }
  sumAll(share, buf);
  throwIfFailed(buf.back(), error);
  s.assign(buf.begin(), buf.begin() + k);
  count = static_cast<int>(buf[k]);
}

// ||A||_F^2 (Teuchos' normFrobenius takes a magnitude and a branch per entry: 4% of an update).
double sumSquares(const DenseMatrix& A) {
  double sum = 0.0;
  for (int j = 0; j < A.numCols(); ++j) {
    const double* a = A[j];
    for (int i = 0; i < A.numRows(); ++i) sum += a[i] * a[i];
  }
  return sum;
}

// eq:update_error gives ||S^T R + a b^T C||_F^2 = before^2 - sum_{i<=r} lambda_i without a product
// over wbar; its absolute rounding error is a few eps before^2, so it is used while the result
// stays above kIdentityFloor before^2 (relative error below ~1e-11), and the residual is formed
// directly below that, where the subtraction would cancel.
constexpr double kIdentityFloor = 1e-4;

// ||S^T R + a b^T C||_F (X = S^T R on the own rows, before2 = ||S^T R||_F^2 over all rows).
// Collective when the identity is not used; every rank takes the same branch (replicated inputs).
double residualAfter(const AdeimUpdate& up, DenseMatrix& X, const SampledRowShare& share, double before2) {
  double sum = 0.0;
  for (int i = 0; i < up.rank; ++i) sum += up.eigenvalues[i];
  if (before2 - sum > kIdentityFloor * before2) return std::sqrt(before2 - sum);
  const DenseMatrix g = product(TRANS, NO_TRANS, up.C, up.b);  // wbar x r: C^T b_i
  const int own = X.numRows();
  DenseMatrix aOwn(own, up.rank);
  for (int c = 0; c < up.rank; ++c)
    for (int i = 0; i < own; ++i) aOwn(i, c) = up.a(share.positions[i], c);
  if (up.rank > 0) X.multiply(NO_TRANS, TRANS, 1.0, aOwn, g, 1.0);
  std::vector<double> after{sumSquares(X)};
  sumAll(share, after);
  return std::sqrt(after[0]);
}
}  // namespace

// Each rank forms S^T R on its rows, X = S^T U C - S^T F, and M = X Q_1; one sum-reduction
// assembles M (and, after a cut, X C^T for the tau_r test) with the norms and a non-finite flag,
// so every rank then runs the same small dense algebra and throws (or not) together.
AdeimUpdate computeAdeimUpdate(const CoefficientFactor& cf, const DenseMatrix& StU, const DenseMatrix& StF,
                               const AdeimUpdateOptions& opt, const SampledRowShare& share) {
  const int m = cf.C.numRows(), own = StU.numRows(), ms = share.numRows, wbar = cf.C.numCols(), rc = cf.rank();
  GPHR_REQUIRE(opt.rank >= 0 && opt.rankTol >= 0.0, InputError, "GP-ADEIM update: rank ", opt.rank, ", rankTol ",
               opt.rankTol, " (need non-negative values)");
  // This rank's inputs are checked here but refused only after the reduction, on every rank
  // together: a throw before it would leave the other ranks waiting.
  bool shapeOk = StU.numCols() == m && StF.numRows() == own && StF.numCols() == wbar &&
                 static_cast<int>(share.positions.size()) == own && own <= ms;
  for (int p : share.positions) shapeOk = shapeOk && p >= 0 && p < ms;
  const std::string shapeError =
      shapeOk ? std::string()
              : detail::concat("GP-ADEIM update: S^T U is ", own, " x ", StU.numCols(), ", S^T F ", StF.numRows(),
                               " x ", StF.numCols(), " for ", share.positions.size(), " positions among ", ms,
                               " sampling rows (need own x m and own x wbar with m = ", m, ", wbar = ", wbar,
                               ", positions in 0 .. m_s - 1)");
  AdeimUpdate up;
  up.C = cf.C;
  const size_t mSize = static_cast<size_t>(ms) * rc, xcSize = cf.cut ? static_cast<size_t>(ms) * m : 0;
  std::vector<double> buf(mSize + xcSize + 5, 0.0);
  double* tail = buf.data() + mSize + xcSize;
  DenseMatrix X;
  if (shapeOk) {
    X = product(NO_TRANS, NO_TRANS, StU, up.C);  // S^T R = S^T U C - S^T F (own rows)
    tail[0] = sumSquares(X);
    X -= StF;
    if (rc > 0) scatterOwnRows(product(NO_TRANS, NO_TRANS, X, cf.Q), share, buf, 0);
    if (cf.cut) scatterOwnRows(product(NO_TRANS, TRANS, X, up.C), share, buf, mSize);
    tail[1] = sumSquares(StF);
    tail[2] = sumSquares(X);
    tail[3] = allFinite(StF) && allFinite(StU) ? 0.0 : 1.0;
  }
  tail[4] = shapeOk ? 0.0 : 1.0;
  sumAll(share, buf);
  tail = buf.data() + mSize + xcSize;
  GPHR_REQUIRE(tail[4] == 0.0, InputError,
               shapeOk ? "GP-ADEIM update: mismatched sampling-row inputs on another rank" : shapeError);
  GPHR_REQUIRE(tail[3] == 0.0, InputError,
               "GP-ADEIM update: non-finite entries in the snapshot window or the DEIM basis rows");
  up.residualBefore = up.residualAfter = std::sqrt(tail[2]);
  up.a.shape(ms, 0);
  up.b.shape(m, 0);
  // A residual at the round-off level of its own subtraction is zero: no update (U unchanged).
  const double roundoff = 100.0 * std::numeric_limits<double>::epsilon() * (std::sqrt(tail[0]) + std::sqrt(tail[1]));
  if (up.residualBefore <= roundoff) return up;
  up.coefficientRank = rc;
  if (rc == 0) return up;
  const DenseMatrix M = columnMajor(buf, 0, ms, rc);
  const DenseMatrix R = rFactor(M);  // M = Q_M R: M's singular values and right vectors are R's
  // The tau_r test on S^T R C^T: with nothing cut, C^T = Q_1 T, so S^T R C^T = M T = Q_M (R T)
  // has the singular values of the small min(m_s, r_C) x m matrix R T (no product over wbar, no
  // SVD of m_s rows); after a cut, of the product itself (assembled above). Independent of the
  // singular values of R, so the two run side by side (splitSingularValues).
  const bool test = opt.rank == 0;
  DenseMatrix Z;
  if (test) Z = cf.cut ? columnMajor(buf, mSize, ms, m) : product(NO_TRANS, NO_TRANS, R, cf.T);
  std::vector<double> sigma;
  int count = 0;
  splitSingularValues(share, R, test ? &Z : nullptr, opt.rankTol, sigma, count);
  const int rbar = countAbove(sigma, std::max(ms, rc) * std::numeric_limits<double>::epsilon());
  for (int i = 0; i < rbar; ++i) up.eigenvalues.push_back(sigma[i] * sigma[i]);
  const int r = test ? std::min(count, rbar) : std::min(opt.rank, rbar);
  up.rank = r;
  // b_i = T^+ w_i, w_i the right singular vectors of M: the least-norm b_i with T b_i = w_i, in
  // range(C) as the paper's b_i = Q_j z_i (see pseudoInverse). Then (Q_1 T)^T b_i = Q_1 w_i, so
  // ||C^T b_i|| = 1 and eq:ai_from_bi, a_i = -S^T R C^T b_i / ||C^T b_i||^2, is -M w_i: no product
  // over wbar. After a cut this is the update for C's rank-r_C truncation T^T Q_1^T (the route of
  // Peherstorfer & Willcox's Lemma 3.4 the paper follows); the dropped part of C^T, below
  // coefficientTol |R_11|, is left out of the objective as it is left out of C. With r = r_C (most
  // updates: 534 of 600 on the paper's NLS run) W is square and orthogonal, and only a b^T =
  // -M W W^T T^+^T = -M T^+^T enters U: then (a, b) = (-M, T^+) is the same update without the
  // singular vectors (their columns span what the eigenvectors span, not the eigenvectors).
  if (r == rc) {
    up.b = cf.Tinv;
    up.a = M;
    up.a.scale(-1.0);
  } else if (r > 0) {
    const ThinSvd svd = thinSvd(R);  // every rank: the same call on the same replicated data
    DenseMatrix W(rc, r);            // w_1 .. w_r
    for (int i = 0; i < r; ++i)
      for (int l = 0; l < rc; ++l) W(l, i) = svd.Vt(i, l);
    up.b = product(NO_TRANS, NO_TRANS, cf.Tinv, W);
    up.a.shape(ms, r);
    up.a.multiply(NO_TRANS, NO_TRANS, -1.0, M, W, 0.0);
  }
  up.residualAfter = residualAfter(up, X, share, tail[2]);
  return up;
}

void applyAdeimUpdate(const AdeimUpdate& up, const SampledRowShare& share, DenseMatrix& StU) {
  GPHR_REQUIRE(static_cast<int>(share.positions.size()) == StU.numRows() && StU.numCols() == up.b.numRows() &&
                   share.numRows == up.a.numRows(),
               InputError, "GP-ADEIM update: ", StU.numRows(), " x ", StU.numCols(), " own rows of S^T U for ",
               share.positions.size(), " positions, the update ", up.a.numRows(), " x ", up.b.numRows());
  if (up.rank == 0) return;
  DenseMatrix aOwn(StU.numRows(), up.rank);
  for (int c = 0; c < up.rank; ++c)
    for (int i = 0; i < StU.numRows(); ++i) aOwn(i, c) = up.a(share.positions[i], c);
  StU.multiply(NO_TRANS, TRANS, 1.0, aOwn, up.b, 1.0);
}

void applyAdeimUpdate(const AdeimUpdate& up, DenseMatrix& StU) {
  GPHR_REQUIRE(StU.numRows() == up.a.numRows() && StU.numCols() == up.b.numRows(), InputError,
               "GP-ADEIM update: S^T U is ", StU.numRows(), " x ", StU.numCols(), ", the update ", up.a.numRows(),
               " x ", up.b.numRows());
  if (up.rank > 0) StU.multiply(NO_TRANS, TRANS, 1.0, up.a, up.b, 1.0);
}

}  // namespace gphr
