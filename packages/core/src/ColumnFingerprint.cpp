#include "gphr/core/ColumnFingerprint.hpp"

#include <cmath>

#include "gphr/core/IndexHash.hpp"

namespace gphr {

std::vector<double> columnFingerprint(const MultiVector& X, double* wNorm) {
  Vector w(X.getMap());
  {
    auto v = w.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (size_t i = 0; i < v.extent(0); ++i) {
      const unsigned long long x = hashIndex(0, static_cast<unsigned long long>(X.getMap()->getGlobalElement(i)));
      v(i, 0) = static_cast<double>(x >> 11) * 0x1.0p-52 - 1.0;  // [-1, 1)
    }
  }
  if (wNorm) *wNorm = w.norm2();
  auto local = rcp(new Map(X.getNumVectors(), 0, X.getMap()->getComm(), Tpetra::LocallyReplicated));
  MultiVector c(local, 1);
  c.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, X, w, 0.0);
  auto cv = c.getLocalViewHost(Tpetra::Access::ReadOnly);
  std::vector<double> out(X.getNumVectors());
  for (size_t j = 0; j < out.size(); ++j) out[j] = cv(j, 0);
  return out;
}

bool fingerprintMatches(const std::vector<double>& stored, const MultiVector& X) {
  return stored.size() == X.getNumVectors() && firstMismatchingColumn(stored, X) < 0;
}

long firstMismatchingColumn(const std::vector<double>& stored, const MultiVector& X) {
  double wNorm = 0.0;
  const std::vector<double> now = columnFingerprint(X, &wNorm);
  std::vector<double> norms(X.getNumVectors());
  X.norm2(Teuchos::ArrayView<double>(norms));
  for (size_t j = 0; j < now.size(); ++j)
    if (j >= stored.size() || !(std::abs(stored[j] - now[j]) <= 1e-9 * wNorm * norms[j])) return static_cast<long>(j);
  return -1;
}

}  // namespace gphr
