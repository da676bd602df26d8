#pragma once
/// @file
/// Thin SVD of a small or tall dense matrix by LAPACK GESDD (divide and conquer), which
/// Teuchos::LAPACK (Trilinos 13.2) does not wrap. It is backward stable like GESVD and about twice
/// as fast with vectors on the shapes GPHR meets (GP-ADEIM's 100 x 400 and 250 x 100 matrices:
/// 4.9 vs 8.3 ms and 3.6 vs 7.4 ms; the streaming POD's stacked R factors). At these sizes a dense
/// LAPACK call is the right tool; Anasazi's iterative solvers would cost more than they save.
namespace gphr {

/// a: m x n, column-major, leading dimension lda, overwritten. s: min(m, n) singular values,
/// descending. With vectors: u (m x min(m, n), leading dimension ldu) and vt (min(m, n) x n,
/// leading dimension ldvt); without, u and vt are not touched (may be null). SolverError naming
/// `what` and the shape if LAPACK fails.
void denseThinSvd(int m, int n, double* a, int lda, double* s, double* u, int ldu, double* vt, int ldvt, bool vectors,
                  const char* what);

}  // namespace gphr
