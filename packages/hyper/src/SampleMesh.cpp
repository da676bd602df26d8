#include "gphr/hyper/SampleMesh.hpp"

#include "gphr/core/Error.hpp"
#include "gphr/core/ReplicatedGather.hpp"

namespace gphr {

size_t SampleMesh::numbersHeld() const {
  const size_t r = static_cast<size_t>(sample.reducedDim);
  return sample.rows.size() * 2 + sample.stencil.offsets.size() + sample.stencil.gids.size() +
         sample.weights.size() + sample.basisRows.size() + sample.reference.size() + r * r + r + 1;
}

RowSample gatherRowSample(const HamiltonianSystem& system, const MultiVector& A, const std::vector<GO>& rows,
                          const std::vector<double>& weights) {
  GPHR_REQUIRE(rows.size() == weights.size() && !rows.empty(), InputError, "sample mesh: ", rows.size(),
               " rows and ", weights.size(), " weights (need the same number, at least one)");
  RowSample s;
  s.rows = rows;
  s.weights = weights;
  s.reducedDim = static_cast<int>(A.getNumVectors());
  s.stencil = gatherStencils(system.nonlinearTerm(), rows);
  s.basisRows = gatherRows(A, s.stencil.gids);
  s.shifted = !system.reference().is_null();
  s.reference = s.shifted ? gatherRows(*system.reference(), s.stencil.gids)
                          : std::vector<double>(s.stencil.gids.size(), 0.0);
  return s;
}

SampleMesh buildSampleMesh(const HamiltonianSystem& system, const MultiVector& A, const std::vector<GO>& rows,
                           const std::vector<double>& weights, ReducedLinearPart linear) {
  SampleMesh mesh;
  mesh.sample = gatherRowSample(system, A, rows, weights);
  mesh.linear = std::move(linear);
  return mesh;
}

}  // namespace gphr
