#pragma once
/// @file
/// The sample mesh of the hyper-reduced model (DESIGN.md): for the m sampled rows of G their
/// stencils, the rows of A under them, y0 there (the shift), the DEIM weights, and L_r, f_r, c.
/// This is everything the online phase holds: O(m s k + k^2) numbers, nothing of size n or d.
#include "gphr/core/ReplicatedGather.hpp"
#include "gphr/reduction/ReducedHamiltonian.hpp"

namespace gphr {

/// The sample mesh: everything the online hyper-reduced model holds (see the file's description).
struct SampleMesh {
  RowSample sample;          ///< rows, stencils, basis rows (m s x 2k), y0 on the stencils, weights
  ReducedLinearPart linear;  ///< L_r, f_r, c
  /// Numbers held: the online object's memory in doubles (independent of n and d).
  size_t numbersHeld() const;
};

/// The rows `rows` of G with their stencils, the rows of A and y0 under them, and the weights:
/// gathered collectively, replicated (also GP-ADEIM's moving interpolation and sampling rows).
RowSample gatherRowSample(const HamiltonianSystem& system, const MultiVector& A, const std::vector<GO>& rows,
                          const std::vector<double>& weights);

/// The same, reusing the rows already held in `known` (a previous sample of the same system and
/// basis): only rows not in it are gathered. Collective; every rank passes the same arguments.
RowSample gatherRowSample(const HamiltonianSystem& system, const MultiVector& A, const std::vector<GO>& rows,
                          const std::vector<double>& weights, const RowSample& known);
/// The same from a row-major copy of A's local rows (repeated gathers: GP-ADEIM's moving rows).
RowSample gatherRowSample(const HamiltonianSystem& system, const LocalRows& A, const std::vector<GO>& rows,
                          const std::vector<double>& weights, const RowSample& known);

/// The rows of G whose stencils hold one of `entries` (state gids, ascending): marked by their
/// owners, summed over the ranks (d integers, once, offline). Collective.
std::vector<GO> rowsTouching(const NonlinearTerm& term, const std::vector<GO>& entries);

/// Gathers (collectively) what the rows `rows` of the system's G need; weights one per row.
SampleMesh buildSampleMesh(const HamiltonianSystem& system, const MultiVector& A, const std::vector<GO>& rows,
                           const std::vector<double>& weights, ReducedLinearPart linear);

}  // namespace gphr
