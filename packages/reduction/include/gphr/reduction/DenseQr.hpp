#pragma once
/// @file
/// Householder QR of a small tall dense matrix by LAPACK GEQRT (compact-WY blocks of a size the
/// caller sets), which Teuchos::LAPACK (Trilinos 13.2) does not wrap. Why not GEQRF: reference
/// LAPACK's GEQRF (as in Debian's OpenBLAS) runs its unblocked Level-2 loop until the column
/// count passes ILAENV's crossover of 128, so at GP-ADEIM's 250 x 100 it takes 0.57 ms against
/// 0.29 ms for GEQRT with blocks of 32 (one thread, CPU time). Same Householder arithmetic, so
/// the same backward stability.
namespace gphr {

/// The R factor (n x n upper triangular, column-major into r with leading dimension ldr) of the
/// m x n column-major matrix a (m >= n, leading dimension lda; overwritten by the reflectors).
/// SolverError naming `what` and the shape if LAPACK fails.
void denseQrFactorR(int m, int n, double* a, int lda, double* r, int ldr, const char* what);

}  // namespace gphr
