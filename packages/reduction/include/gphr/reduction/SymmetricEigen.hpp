#pragma once
/// @file
/// Small dense symmetric eigenproblems (LAPACK SYEVD with its workspace query): the Gram matrix of
/// the randomized DEIM basis, the Hessian convexity check, GP-ADEIM's re-orthonormalization. At
/// these sizes (m, 2k <= a few hundred) a dense LAPACK call is the right tool, not Anasazi.
#include <vector>

namespace gphr {

/// Eigenvalues, ascending, of the symmetric n x n column-major matrix a (leading dimension n,
/// upper triangle read). With vectors, a is overwritten by the orthonormal eigenvectors (column j
/// for eigenvalue j). SolverError naming `what` if LAPACK fails.
std::vector<double> symmetricEigen(int n, double* a, bool vectors, const char* what);

}  // namespace gphr
