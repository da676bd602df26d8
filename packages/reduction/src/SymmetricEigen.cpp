#include "gphr/reduction/SymmetricEigen.hpp"

#include <Teuchos_LAPACK.hpp>
#include <algorithm>

#include "gphr/core/Error.hpp"

namespace gphr {

std::vector<double> symmetricEigen(int n, double* a, bool vectors, const char* what) {
  std::vector<double> lambda(n), work(1);
  const char jobz = vectors ? 'V' : 'N';
  Teuchos::LAPACK<int, double> lapack;
  int info = 0;
  lapack.SYEV(jobz, 'U', n, a, n, lambda.data(), work.data(), -1, &info);
  work.resize(std::max(1, static_cast<int>(work[0])));
  lapack.SYEV(jobz, 'U', n, a, n, lambda.data(), work.data(), static_cast<int>(work.size()), &info);
  GPHR_REQUIRE(info == 0, SolverError, what, ": LAPACK SYEV failed (info = ", info, ")");
  return lambda;
}

}  // namespace gphr
