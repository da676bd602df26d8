#include "gphr/reduction/Deim.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_LAPACK.hpp>

#include <cmath>

#include "gphr/core/Error.hpp"
#include "gphr/core/ReplicatedGather.hpp"

namespace gphr {

namespace {
using Lapack = Teuchos::LAPACK<int, double>;

// Global argmax of |x| over the map (ties: smallest gid); returns (gid, |x|). One gatherAll of
// (value, gid) pairs (gids are exact in a double below 2^53).
std::pair<GO, double> argmaxAbs(const Map& map, const double* x) {
  double best[2] = {-1.0, -1.0};  // |x|, gid
  for (LO i = 0; i < static_cast<LO>(map.getNodeNumElements()); ++i) {
    const double a = std::abs(x[i]), g = static_cast<double>(map.getGlobalElement(i));
    if (a > best[0] || (a == best[0] && g < best[1])) best[0] = a, best[1] = g;
  }
  const int np = map.getComm()->getSize();
  std::vector<double> all(2 * static_cast<size_t>(np));
  Teuchos::gatherAll(*map.getComm(), 2, best, 2 * np, all.data());
  std::pair<GO, double> out{-1, -1.0};
  for (int p = 0; p < np; ++p) {
    const double v = all[2 * p], g = all[2 * p + 1];
    if (g >= 0.0 && (v > out.second || (v == out.second && static_cast<GO>(g) < out.first)))
      out = {static_cast<GO>(g), v};
  }
  return out;
}

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

std::vector<GO> greedyDeim(const MultiVector& U, int m) {
  const Map& map = *U.getMap();
  const LO nl = static_cast<LO>(map.getNodeNumElements());
  auto u = U.getLocalViewHost(Tpetra::Access::ReadOnly);
  std::vector<GO> idx;
  std::vector<double> PtU;  // rows of U at idx (replicated), row-major with U.cols entries
  std::vector<double> res(nl);
  const int nc = static_cast<int>(U.getNumVectors());
  for (int l = 0; l < m; ++l) {
    // c = (P^T U_l)^{-1} P^T u_l;  res = u_l - U_l c
    std::vector<double> B(static_cast<size_t>(l) * l), c(l);
    for (int i = 0; i < l; ++i) {
      c[i] = PtU[static_cast<size_t>(i) * nc + l];
      for (int j = 0; j < l; ++j) B[i + static_cast<size_t>(l) * j] = PtU[static_cast<size_t>(i) * nc + j];
    }
    if (l > 0) luSolve(B, l, c, 'N', "greedy DEIM");
    for (LO i = 0; i < nl; ++i) res[i] = u(i, l);
    for (int j = 0; j < l; ++j)  // column by column: U is column-major (LayoutLeft)
      for (LO i = 0; i < nl; ++i) res[i] -= u(i, j) * c[j];
    const auto [gid, val] = argmaxAbs(map, res.data());
    GPHR_REQUIRE(val > 0.0 && std::isfinite(val), InputError, "greedy DEIM: the residual of DEIM basis column ",
                 l + 1, " vanishes (", val, "): the DEIM basis is rank-deficient; use m <= ", l);
    idx.push_back(gid);
    const auto row = gatherRows(U, {gid});
    PtU.insert(PtU.end(), row.begin(), row.end());
  }
  return idx;
}

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

DeimWeights computeDeimWeights(const MultiVector& U, const std::vector<GO>& indices, const Vector& v) {
  const int m = static_cast<int>(indices.size()), nc = static_cast<int>(U.getNumVectors());
  GPHR_REQUIRE(m >= 1 && m <= nc, InputError, "DEIM weights: ", m, " indices for a basis of ", nc, " columns");
  auto local = rcp(new Map(nc, 0, U.getMap()->getComm(), Tpetra::LocallyReplicated));
  MultiVector Utv(local, 1);
  Utv.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, U, v, 0.0);
  const std::vector<double> rows = gatherRows(U, indices);  // (P^T U)(i, j) = rows[i * nc + j]
  std::vector<double> B = pointRows(rows, m, nc);
  DeimWeights out;
  out.conditionNumber = conditionNumber(B, m);
  out.weights.resize(m);
  auto c = Utv.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (int j = 0; j < m; ++j) out.weights[j] = c(j, 0);
  luSolve(B, m, out.weights, 'T', "DEIM weights");  // (P^T U)^T x = U^T v
  return out;
}

}  // namespace gphr
