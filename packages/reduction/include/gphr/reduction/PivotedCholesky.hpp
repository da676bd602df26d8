#pragma once
/// @file
/// Pivoted Cholesky factorization of a small symmetric positive semi-definite matrix (LAPACK
/// PSTRF, which Teuchos::LAPACK in Trilinos 13.2 does not wrap): Pi^T G Pi = R^T R with the
/// largest remaining diagonal pivoted first. For a Gram matrix G = U^T U this is what column-pivoted
/// QR of U gives (R the same up to signs), at O(m^3) on the m x m Gram matrix instead of O(d m^2).
#include <vector>

#include "gphr/core/DenseTypes.hpp"

namespace gphr {

/// Result of pivotedCholeskyInverse(): numerical rank, pivot order and R^{-1}.
struct PivotedCholesky {
  int rank = 0;           ///< pivots above LAPACK's default tolerance (n eps max G_ii)
  std::vector<int> perm;  ///< column i of G Pi is column perm[i] of G (0-based)
  DenseMatrix Rinv;       ///< R^{-1} (rank x rank, upper triangular): U Pi R^{-1} is orthonormal
};

/// G is read (n x n, symmetric; the upper triangle is used). SolverError if LAPACK fails.
PivotedCholesky pivotedCholeskyInverse(const DenseMatrix& G);

}  // namespace gphr
