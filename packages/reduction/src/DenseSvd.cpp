#include "gphr/reduction/DenseSvd.hpp"

#include <algorithm>
#include <vector>

#include "gphr/core/Error.hpp"

extern "C" void dgesdd_(const char* jobz, const int* m, const int* n, double* a, const int* lda, double* s, double* u,
                        const int* ldu, double* vt, const int* ldvt, double* work, const int* lwork, int* iwork,
                        int* info);

namespace gphr {

void denseThinSvd(int m, int n, double* a, int lda, double* s, double* u, int ldu, double* vt, int ldvt, bool vectors,
                  const char* what) {
  const int mn = std::min(m, n);
  if (mn == 0) return;
  const char jobz = vectors ? 'S' : 'N';
  double dummy = 0.0;
  if (!vectors) {
    u = vt = &dummy;
    ldu = ldvt = 1;
  }
  lda = std::max(1, lda);
  ldu = std::max(1, ldu);
  ldvt = std::max(1, ldvt);
  std::vector<double> work(1);
  std::vector<int> iwork(8 * static_cast<size_t>(mn));
  int info = 0, lwork = -1;
  dgesdd_(&jobz, &m, &n, a, &lda, s, u, &ldu, vt, &ldvt, work.data(), &lwork, iwork.data(), &info);
  lwork = std::max(1, static_cast<int>(work[0]));
  work.resize(lwork);
  dgesdd_(&jobz, &m, &n, a, &lda, s, u, &ldu, vt, &ldvt, work.data(), &lwork, iwork.data(), &info);
  GPHR_REQUIRE(info == 0, SolverError, what, ": LAPACK GESDD failed (info = ", info, ") on a ", m, " x ", n,
               " matrix");
}

}  // namespace gphr
