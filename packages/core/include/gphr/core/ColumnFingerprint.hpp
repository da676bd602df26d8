#pragma once
/// @file
/// A fingerprint of distributed columns that does not depend on the rank count: X^T w, with
/// w_i in [-1, 1) a hash (hashIndex) of row i's global index. What a file stores beside
/// distributed data that no checksum covers (a model file's basis, a validation's full-model
/// trajectory), checked where the data are read back: an entry x_ij changed by delta moves
/// component j by w_i delta.
#include <string>
#include <vector>

#include "gphr/core/Types.hpp"

namespace gphr {

/// X^T w (one number per column); ||w|| into `wNorm` if given. Collective over X's map.
std::vector<double> columnFingerprint(const MultiVector& X, double* wNorm = nullptr);

/// Whether `stored` is X's fingerprint to round-off: |stored_j - (X^T w)_j| <= 1e-9 ||w|| ||x_j||
/// for every column. x_j^T w sums terms of total size <= ||x_j|| ||w||; summed in another order
/// (other ranks) the two differ by ~sqrt(rows) eps ||x_j|| ||w|| (4.2e-17 ||w|| measured for
/// orthonormal columns written on 1 and 3 ranks, 256 rows), so 1e-9 leaves a margin of 1e4 at
/// 1e7 rows and still catches a change of an entry by more than 1e-9 ||x_j|| ||w|| / |w_i|.
/// Collective.
bool fingerprintMatches(const std::vector<double>& stored, const MultiVector& X);

/// The first column of X that does not match `stored` as fingerprintMatches judges it, or -1 if
/// all do; a column beyond stored's end does not match. Collective.
long firstMismatchingColumn(const std::vector<double>& stored, const MultiVector& X);

}  // namespace gphr
