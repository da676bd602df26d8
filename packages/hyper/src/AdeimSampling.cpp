#include "gphr/hyper/AdeimSampling.hpp"

#include <Teuchos_BLAS.hpp>
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_OrdinalTraits.hpp>
#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <set>

#include "gphr/core/Error.hpp"

namespace gphr {

// A row-major rows x wbar array is a column-major wbar x rows one (F^T). The products are formed
// column-major, rows x len (X = U T^T - F Q_1: GEMM(N, T) and GEMM(T, N) with F^T as the
// transposed operand), and the row norms accumulated column by column: OpenBLAS runs this shape
// at 2.3 ms against 3.0 ms for the transposed output len x rows (paper size, 1024 own rows, wbar =
// 400, len = 100; one thread, CPU time). Projected: (U C - F) Q_1 without forming R, and with
// C Q_1 = T^T exactly (C^T = Q_1 T + Q_2 T_2 with Q_2 orthogonal to Q_1, cut or not): no product
// over wbar for it.
std::vector<double> residualRowNorms(const double* U, int ldU, const std::vector<double>& Fl, int rows,
                                     const CoefficientFactor& cf, bool projected) {
  const DenseMatrix& C = cf.C;
  const int m = C.numRows(), wbar = C.numCols();
  GPHR_REQUIRE(rows >= 0 && ldU >= std::max(rows, 1) && Fl.size() == static_cast<size_t>(rows) * wbar, InputError,
               "sampling scores: leading dimension ", ldU, " and ", Fl.size(), " snapshot entries for ", rows,
               " rows (need ldU >= rows and rows x ", wbar, " entries)");
  std::vector<double> out(rows, 0.0);
  if (rows == 0) return out;
  Teuchos::BLAS<int, double> blas;
  const int len = projected ? cf.rank() : wbar;
  if (len == 0) return out;
  // Column-major rows x len, not zero-filled (each GEMM below starts with beta = 0 or after one).
  const std::unique_ptr<double[]> buffer(new double[static_cast<size_t>(rows) * len]);
  double* X = buffer.get();
  if (projected) {
    blas.GEMM(Teuchos::NO_TRANS, Teuchos::TRANS, rows, len, m, 1.0, U, ldU, cf.T.values(), cf.T.stride(), 0.0, X, rows);
    blas.GEMM(Teuchos::TRANS, Teuchos::NO_TRANS, rows, len, wbar, -1.0, Fl.data(), wbar, cf.Q.values(), cf.Q.stride(),
              1.0, X, rows);
  } else {
    blas.GEMM(Teuchos::NO_TRANS, Teuchos::NO_TRANS, rows, len, m, 1.0, U, ldU, C.values(), C.stride(), 0.0, X,
              rows);
    for (int c = 0; c < len; ++c)  // - F: F^T's column i is row i of F
      for (int i = 0; i < rows; ++i) X[static_cast<size_t>(c) * rows + i] -= Fl[static_cast<size_t>(i) * wbar + c];
  }
  for (int c = 0; c < len; ++c) {
    const double* x = X + static_cast<size_t>(c) * rows;
    for (int i = 0; i < rows; ++i) out[i] += x[i] * x[i];
  }
  for (double& v : out) v = std::sqrt(v);
  return out;
}

namespace {
struct Candidate {
  double score;
  long long gid;
};
bool better(const Candidate& a, const Candidate& b) {
  return a.score > b.score || (a.score == b.score && a.gid < b.gid);
}
}  // namespace

// Each rank offers its K best rows (K = m_s, or the cap with tau_s), sorted; one gather of the
// offers as (score, gid) pairs in doubles (gids exact below 2^53) and the same selection on every
// rank. The excluded rows are marked by local index (no set lookups per row).
std::vector<GO> largestScoreRows(const Map& rowMap, const std::vector<double>& scores, const std::vector<GO>& exclude,
                                 const SampleCount& count) {
  const LO nl = static_cast<LO>(rowMap.getNodeNumElements());
  GPHR_REQUIRE(static_cast<LO>(scores.size()) == nl, InputError, "sampling: ", scores.size(), " scores for ", nl,
               " local rows");
  const int K = count.fixed > 0 ? count.fixed : count.atMost;
  GPHR_REQUIRE(K > 0 && count.atLeast <= std::max(K, count.atLeast), InputError, "sampling: asked for ", K,
               " rows (at least ", count.atLeast, ")");
  std::vector<char> skip(nl, 0);
  for (GO g : exclude) {
    const LO l = rowMap.getLocalElement(g);
    if (l != Teuchos::OrdinalTraits<LO>::invalid()) skip[l] = 1;
  }
  std::vector<Candidate> local;
  local.reserve(nl);
  for (LO i = 0; i < nl; ++i) {
    GPHR_REQUIRE(std::isfinite(scores[i]), SolverError, "sampling: non-finite residual at row ",
                 rowMap.getGlobalElement(i));
    if (!skip[i]) local.push_back({scores[i], static_cast<long long>(rowMap.getGlobalElement(i))});
  }
  const size_t keep = std::min(local.size(), static_cast<size_t>(K));
  if (keep < local.size()) std::nth_element(local.begin(), local.begin() + keep, local.end(), better);
  std::sort(local.begin(), local.begin() + keep, better);
  std::vector<double> offer(2 * static_cast<size_t>(K), -1.0), all;  // (score, gid); gid -1: no row
  for (size_t i = 0; i < keep; ++i) offer[2 * i] = local[i].score, offer[2 * i + 1] = static_cast<double>(local[i].gid);
  const int np = rowMap.getComm()->getSize();
  all.resize(static_cast<size_t>(np) * offer.size());
  Teuchos::gatherAll(*rowMap.getComm(), static_cast<int>(offer.size()), offer.data(), static_cast<int>(all.size()),
                     all.data());
  std::vector<Candidate> merged;
  merged.reserve(all.size() / 2);
  for (size_t i = 0; i < all.size(); i += 2)
    if (all[i + 1] >= 0.0) merged.push_back({all[i], static_cast<long long>(all[i + 1])});
  size_t n = std::min(merged.size(), static_cast<size_t>(K));
  std::partial_sort(merged.begin(), merged.begin() + n, merged.end(), better);
  if (count.fixed <= 0 && !merged.empty()) {
    const double floor = count.relTol * merged.front().score;
    size_t above = 0;
    while (above < n && merged[above].score > floor) ++above;
    n = std::min(n, std::max(above, static_cast<size_t>(count.atLeast)));
  }
  std::vector<GO> rows;
  rows.reserve(n);
  for (size_t i = 0; i < n; ++i) rows.push_back(static_cast<GO>(merged[i].gid));
  std::sort(rows.begin(), rows.end());
  return rows;
}

std::vector<GO> randomRows(const Map& rowMap, const std::vector<GO>& exclude, int count, unsigned long long seed,
                           long draw) {
  GPHR_REQUIRE(rowMap.isContiguous(), InputError, "random sampling needs a contiguous row map of G");
  const GO lo = rowMap.getMinAllGlobalIndex(), hi = rowMap.getMaxAllGlobalIndex();
  const std::set<GO> skip(exclude.begin(), exclude.end());
  const GO available = (hi - lo + 1) - static_cast<GO>(skip.size());
  const GO n = std::min<GO>(count, std::max<GO>(available, 0));
  std::mt19937_64 gen(seed + 0x9E3779B97F4A7C15ull * static_cast<unsigned long long>(draw + 1));
  std::uniform_int_distribution<GO> pick(lo, hi);
  std::set<GO> rows;
  while (static_cast<GO>(rows.size()) < n) {
    const GO g = pick(gen);
    if (!skip.count(g)) rows.insert(g);
  }
  return {rows.begin(), rows.end()};
}

}  // namespace gphr
