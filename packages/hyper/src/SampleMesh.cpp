#include "gphr/hyper/SampleMesh.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <unordered_map>

#include "gphr/core/Error.hpp"
#include "gphr/core/ReplicatedGather.hpp"

namespace gphr {

size_t SampleMesh::numbersHeld() const {
  const size_t r = static_cast<size_t>(sample.reducedDim);
  return sample.rows.size() * 2 + sample.stencil.offsets.size() + sample.stencil.gids.size() +
         sample.weights.size() + sample.basisRows.size() + sample.reference.size() + r * r + r + 1;
}

namespace {
int columns(const MultiVector& A) { return static_cast<int>(A.getNumVectors()); }
int columns(const LocalRows& A) { return A.cols; }

template <class Basis>
RowSample gatherFresh(const HamiltonianSystem& system, const Basis& A, const std::vector<GO>& rows,
                      const std::vector<double>& weights) {
  GPHR_REQUIRE(rows.size() == weights.size() && !rows.empty(), InputError, "sample mesh: ", rows.size(),
               " rows and ", weights.size(), " weights (need the same number, at least one)");
  RowSample s;
  s.rows = rows;
  s.weights = weights;
  s.reducedDim = columns(A);
  s.stencil = gatherStencils(system.nonlinearTerm(), rows);
  s.basisRows = gatherRows(A, s.stencil.gids);
  s.shifted = !system.reference().is_null();
  s.reference = s.shifted ? gatherRows(*system.reference(), s.stencil.gids)
                          : std::vector<double>(s.stencil.gids.size(), 0.0);
  return s;
}

// Rows already in `known` are copied from it; only the others are gathered (collectively: every
// rank holds the same `known` and `rows`, so they agree on which rows are new, and when none is,
// no rank communicates). GP-ADEIM re-chooses its interpolation rows at every update (in the paper's
// NLS run about 85 of 100 change); the basis A and y0 do not change, so the rows it keeps need no
// new gather.
template <class Basis>
RowSample gatherKnown(const HamiltonianSystem& system, const Basis& A, const std::vector<GO>& rows,
                      const std::vector<double>& weights, const RowSample& known) {
  GPHR_REQUIRE(rows.size() == weights.size() && !rows.empty(), InputError, "sample mesh: ", rows.size(),
               " rows and ", weights.size(), " weights (need the same number, at least one)");
  const int r = columns(A);
  GPHR_REQUIRE(known.rows.empty() || known.reducedDim == r, InputError, "sample mesh: the known rows have ",
               known.reducedDim, " reduced coordinates, the basis ", r);
  std::unordered_map<GO, size_t> at;  // gid -> row index in known
  for (size_t i = 0; i < known.rows.size(); ++i) at.emplace(known.rows[i], i);
  std::vector<GO> missing;
  for (GO g : rows)
    if (!at.count(g)) missing.push_back(g);
  RowSample fresh;
  if (!missing.empty()) fresh = gatherFresh(system, A, missing, std::vector<double>(missing.size(), 0.0));
  std::unordered_map<GO, size_t> atFresh;
  for (size_t i = 0; i < fresh.rows.size(); ++i) atFresh.emplace(fresh.rows[i], i);
  RowSample s;
  s.rows = rows;
  s.weights = weights;
  s.reducedDim = r;
  s.shifted = !system.reference().is_null();
  for (GO g : rows) {
    const auto k = at.find(g);
    const RowSample& from = k != at.end() ? known : fresh;
    const size_t i = k != at.end() ? k->second : atFresh.at(g);
    const size_t j0 = from.stencil.offsets[i], j1 = from.stencil.offsets[i + 1];
    s.stencil.gids.insert(s.stencil.gids.end(), from.stencil.gids.begin() + j0, from.stencil.gids.begin() + j1);
    s.stencil.offsets.push_back(s.stencil.gids.size());
    s.basisRows.insert(s.basisRows.end(), from.basisRows.begin() + j0 * r, from.basisRows.begin() + j1 * r);
    s.reference.insert(s.reference.end(), from.reference.begin() + j0, from.reference.begin() + j1);
  }
  return s;
}

}  // namespace

RowSample gatherRowSample(const HamiltonianSystem& system, const MultiVector& A, const std::vector<GO>& rows,
                          const std::vector<double>& weights) {
  return gatherFresh(system, A, rows, weights);
}

RowSample gatherRowSample(const HamiltonianSystem& system, const MultiVector& A, const std::vector<GO>& rows,
                          const std::vector<double>& weights, const RowSample& known) {
  return gatherKnown(system, A, rows, weights, known);
}

RowSample gatherRowSample(const HamiltonianSystem& system, const LocalRows& A, const std::vector<GO>& rows,
                          const std::vector<double>& weights, const RowSample& known) {
  return gatherKnown(system, A, rows, weights, known);
}

SampleMesh buildSampleMesh(const HamiltonianSystem& system, const MultiVector& A, const std::vector<GO>& rows,
                           const std::vector<double>& weights, ReducedLinearPart linear) {
  SampleMesh mesh;
  mesh.sample = gatherRowSample(system, A, rows, weights);
  mesh.linear = std::move(linear);
  return mesh;
}

std::vector<GO> rowsTouching(const NonlinearTerm& term, const std::vector<GO>& entries) {
  const GO d = term.numTerms(), base = term.rowMap()->getMinAllGlobalIndex();
  std::vector<int> mark(d, 0), all(d, 0);
  const Stencil& st = term.stencil();
  for (LO i = 0; i < st.numRows(); ++i)
    for (size_t j = st.offsets[i]; j < st.offsets[i + 1]; ++j)
      if (std::binary_search(entries.begin(), entries.end(), st.gids[j]))
        mark[term.rowMap()->getGlobalElement(i) - base] = 1;
  Teuchos::reduceAll(*term.rowMap()->getComm(), Teuchos::REDUCE_SUM, static_cast<int>(d), mark.data(), all.data());
  std::vector<GO> rows;
  for (GO i = 0; i < d; ++i)
    if (all[i]) rows.push_back(base + i);
  return rows;
}

}  // namespace gphr
