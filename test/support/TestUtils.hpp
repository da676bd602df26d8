#pragma once
// Helpers for GPHR's tests: the communicator, reproducible random vectors, FD directions.
#include <Tpetra_Core.hpp>
#include <cmath>

#include <Teuchos_CommHelpers.hpp>

#include "gphr/core/Error.hpp"
#include "gphr/core/Types.hpp"

namespace gphr::test {

inline RCP<const Comm> comm() { return Tpetra::getDefaultComm(); }

// A vector whose entry at global id g is a fixed function of g (so identical on any rank count).
inline void fillByGid(Vector& v, double scale, unsigned seed) {
  auto map = v.getMap();
  auto view = v.getLocalViewHost(Tpetra::Access::OverwriteAll);
  for (LO i = 0; i < static_cast<LO>(map->getNodeNumElements()); ++i) {
    const double g = static_cast<double>(map->getGlobalElement(i));
    view(i, 0) = scale * std::sin(1.3 * g + 0.7 * seed + 0.1 * g * g / (1.0 + g));
  }
}

}  // namespace gphr::test
