#include "gphr/core/ReplicatedGather.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <algorithm>
#include <utility>

#include "gphr/core/Error.hpp"

namespace gphr {

namespace {
// Sum-reduce `local` over the ranks of `comm` (exact here: one contributor per entry).
template <class T>
std::vector<T> sumAll(const Comm& comm, const std::vector<T>& local) {
  std::vector<T> out(local.size(), T(0));
  if (!local.empty())
    Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, static_cast<int>(local.size()), local.data(), out.data());
  return out;
}

// Ownership check shared by the gathers: every id must be owned by exactly one rank. `owners`
// holds the sum over the ranks of each id's ownership flag (carried in the gather's own
// reduction, so the check costs no extra collective), and every rank throws together.
template <class T>
void requireOwnedOnce(const Map& map, const std::vector<GO>& gids, const T* owners, const char* what) {
  for (size_t i = 0; i < gids.size(); ++i) {
    GPHR_REQUIRE(owners[i] != T(0), InputError, what, ": global id ", gids[i],
                 " is not an entry of the map (allowed: 0 to ", map.getMaxAllGlobalIndex(), ")");
    GPHR_REQUIRE(owners[i] == T(1), InputError, what, ": global id ", gids[i], " is owned by ", owners[i],
                 " ranks (the map must be one-to-one)");
  }
}

// The gathers of rows: this rank finds the rows `gids` it owns (their positions i and local
// indices l), `fill(owned, out)` writes their cols entries into out (row i at out + i * cols),
// and one sum-reduction completes them on every rank, with the ownership flags behind them.
template <class Fill>
std::vector<Scalar> gatherOwnedRows(const Map& map, const std::vector<GO>& gids, size_t cols, Fill fill) {
  std::vector<std::pair<size_t, LO>> owned;
  const size_t data = gids.size() * cols;
  std::vector<Scalar> local(data + gids.size(), 0.0);
  for (size_t i = 0; i < gids.size(); ++i) {
    const LO l = map.getLocalElement(gids[i]);
    if (l == Teuchos::OrdinalTraits<LO>::invalid()) continue;
    owned.emplace_back(i, l);
    local[data + i] = 1.0;  // exact: a sum of at most the rank count of ones
  }
  fill(owned, local.data());
  std::vector<Scalar> out = sumAll(*map.getComm(), local);
  requireOwnedOnce(map, gids, out.data() + data, "gatherRows");
  out.resize(data);
  return out;
}
}  // namespace

// Column by column: a MultiVector's local view is column-major, so reading a row at a time
// strides by the local length between entries (a new page per entry at n = 4096, 400 columns:
// 1.7 ms for 170 rows against 0.8 ms column by column, measured in GP-ADEIM's sample-mesh gather).
std::vector<Scalar> gatherRows(const MultiVector& X, const std::vector<GO>& gids) {
  const size_t nc = X.getNumVectors();
  auto x = X.getLocalViewHost(Tpetra::Access::ReadOnly);
  return gatherOwnedRows(*X.getMap(), gids, nc, [&](const std::vector<std::pair<size_t, LO>>& owned, Scalar* out) {
    for (size_t j = 0; j < nc; ++j)
      for (const auto& [i, l] : owned) out[i * nc + j] = x(l, j);
  });
}

std::vector<Scalar> gatherRows(const Map& map, const std::vector<Scalar>& localRows, int cols,
                               const std::vector<GO>& gids) {
  GPHR_REQUIRE(cols >= 0 && localRows.size() == map.getNodeNumElements() * static_cast<size_t>(cols), InputError,
               "gatherRows: ", localRows.size(), " local entries for ", map.getNodeNumElements(), " rows of ", cols,
               " columns");
  const size_t nc = static_cast<size_t>(cols);
  return gatherOwnedRows(map, gids, nc, [&](const std::vector<std::pair<size_t, LO>>& owned, Scalar* out) {
    for (const auto& [i, l] : owned) std::copy_n(localRows.data() + static_cast<size_t>(l) * nc, nc, out + i * nc);
  });
}

LocalRows::LocalRows(const MultiVector& X) : map(X.getMap()), cols(static_cast<int>(X.getNumVectors())) {
  auto x = X.getLocalViewHost(Tpetra::Access::ReadOnly);
  const size_t nl = x.extent(0), nc = x.extent(1);
  rows.resize(nl * nc);
  for (size_t j = 0; j < nc; ++j)
    for (size_t i = 0; i < nl; ++i) rows[i * nc + j] = x(i, j);
}

std::vector<Scalar> gatherRows(const LocalRows& X, const std::vector<GO>& gids) {
  return gatherRows(*X.map, X.rows, X.cols, gids);
}

Stencil gatherStencils(const NonlinearTerm& term, const std::vector<GO>& rows) {
  const Map& rowMap = *term.rowMap();
  const Stencil& own = term.stencil();
  const size_t nr = rows.size();
  std::vector<long long> sizes(2 * nr, 0);  // the stencil sizes, then the ownership flags
  for (size_t i = 0; i < nr; ++i) {
    const LO l = rowMap.getLocalElement(rows[i]);
    if (l != Teuchos::OrdinalTraits<LO>::invalid()) sizes[i] = own.size(l), sizes[nr + i] = 1;
  }
  sizes = sumAll(*rowMap.getComm(), sizes);
  requireOwnedOnce(rowMap, rows, sizes.data() + nr, "gatherStencils (row of G)");
  sizes.resize(nr);
  Stencil out;
  for (long long s : sizes) out.offsets.push_back(out.offsets.back() + static_cast<size_t>(s));
  std::vector<GO> gids(out.offsets.back(), 0);
  for (size_t i = 0; i < rows.size(); ++i) {
    const LO l = rowMap.getLocalElement(rows[i]);
    if (l == Teuchos::OrdinalTraits<LO>::invalid()) continue;
    std::copy(own.gids.begin() + own.offsets[l], own.gids.begin() + own.offsets[l + 1], gids.begin() + out.offsets[i]);
  }
  out.gids = sumAll(*rowMap.getComm(), gids);
  return out;
}

std::vector<Scalar> gatherWeights(const NonlinearTerm& term, const std::vector<GO>& rows) {
  return gatherRows(*term.weights(), rows);
}

}  // namespace gphr
