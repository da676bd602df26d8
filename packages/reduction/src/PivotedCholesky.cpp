#include "gphr/reduction/PivotedCholesky.hpp"

#include <Teuchos_LAPACK.hpp>
#include <vector>

#include "gphr/core/Error.hpp"

extern "C" void dpstrf_(const char* uplo, const int* n, double* a, const int* lda, int* piv, int* rank,
                        const double* tol, double* work, int* info);

namespace gphr {

PivotedCholesky pivotedCholeskyInverse(const DenseMatrix& G) {
  const int n = G.numRows();
  GPHR_REQUIRE(G.numCols() == n, InputError, "pivoted Cholesky: the matrix is ", n, " x ", G.numCols(),
               " (need square)");
  PivotedCholesky out;
  if (n == 0) return out;
  DenseMatrix a(G);
  std::vector<int> piv(n);
  std::vector<double> work(2 * static_cast<size_t>(n));
  const double tol = -1.0;  // LAPACK's default: n eps max_i G_ii
  int rank = 0, info = 0;
  const char uplo = 'U';
  const int lda = a.stride();
  dpstrf_(&uplo, &n, a.values(), &lda, piv.data(), &rank, &tol, work.data(), &info);
  GPHR_REQUIRE(info >= 0, SolverError, "pivoted Cholesky: LAPACK PSTRF failed (info = ", info, ")");
  out.rank = rank;
  out.perm.resize(n);
  for (int i = 0; i < n; ++i) out.perm[i] = piv[i] - 1;
  out.Rinv.shape(rank, rank);
  for (int j = 0; j < rank; ++j)
    for (int i = 0; i <= j; ++i) out.Rinv(i, j) = a(i, j);
  if (rank > 0) {
    Teuchos::LAPACK<int, double> lapack;
    lapack.TRTRI('U', 'N', rank, out.Rinv.values(), out.Rinv.stride(), &info);
    GPHR_REQUIRE(info == 0, SolverError, "pivoted Cholesky: LAPACK TRTRI failed (info = ", info, ")");
  }
  return out;
}

}  // namespace gphr
