#include "gphr/core/DenseTypes.hpp"

namespace gphr {

void applyCanonicalJ(const DenseVector& x, DenseVector& out) {
  const int k = x.length() / 2;
  for (int i = 0; i < k; ++i) {
    out(i) = x(k + i);
    out(k + i) = -x(i);
  }
}

}  // namespace gphr
