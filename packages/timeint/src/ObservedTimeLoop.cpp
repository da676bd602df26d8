#include "gphr/timeint/ObservedTimeLoop.hpp"

namespace gphr {

bool allFinite(const DenseVector& z) {
  for (int i = 0; i < z.length(); ++i)
    if (!std::isfinite(z(i))) return false;
  return true;
}

bool allFinite(const Vector& y) { return std::isfinite(y.norm2()); }

}  // namespace gphr
