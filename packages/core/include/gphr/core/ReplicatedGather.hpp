#pragma once
/// @file
/// Collective gathers of a few distributed rows onto every rank, for the objects the online phase
/// holds replicated (the sample mesh): given global ids listed identically on every rank, each
/// rank fills the entries it owns and one sum-reduction completes them everywhere. Exactly one
/// rank owns each id, so the sum is exact and the result is the same on any rank count.
#include <vector>

#include "gphr/core/NonlinearTerm.hpp"

namespace gphr {

/// Rows `gids` of X (on X's map), row-major: out[i * X.cols + j] = X(gids[i], j). Collective;
/// throws InputError naming an id that no rank owns.
std::vector<Scalar> gatherRows(const MultiVector& X, const std::vector<GO>& gids);

/// Rows `gids` of a row-major array holding this rank's rows of `map` in local order (rows x cols),
/// replicated in the order given. Collective; throws InputError naming an id that no rank owns.
std::vector<Scalar> gatherRows(const Map& map, const std::vector<Scalar>& localRows, int cols,
                               const std::vector<GO>& gids);

/// This rank's rows of a MultiVector, copied once into row-major order for repeated row gathers:
/// a MultiVector's local view is column-major, so reading one row strides by the local length
/// (GP-ADEIM gathers ~170 rows of A per update: 0.8 ms from the MultiVector; from here its whole
/// sample mesh of P took 0.95 instead of 1.55 ms).
/// Holds as many numbers as X's local part.
struct LocalRows {
  explicit LocalRows(const MultiVector& X);  ///< Copies this rank's rows of X into row-major order.
  RCP<const Map> map;  ///< X's map.
  int cols = 0;  ///< Number of columns of X.
  std::vector<Scalar> rows;  ///< local rows x cols, row-major
};
/// Rows `gids` of X from its row-major copy, replicated in the order given. Collective.
std::vector<Scalar> gatherRows(const LocalRows& X, const std::vector<GO>& gids);

/// Stencils of the global rows `rows` of G (any rank may own them), in the order given: the
/// documented stencil layout of NonlinearTerm, replicated. Collective.
Stencil gatherStencils(const NonlinearTerm& term, const std::vector<GO>& rows);

/// Entries rows of the weights v of G. Collective.
std::vector<Scalar> gatherWeights(const NonlinearTerm& term, const std::vector<GO>& rows);

}  // namespace gphr
