#include "gphr/core/Provenance.hpp"

#include <Teuchos_YamlParameterListCoreHelpers.hpp>
#include <sstream>

// Set by packages/core/CMakeLists.txt at configure time.
#ifndef GPHR_VERSION_STRING
#define GPHR_VERSION_STRING "unknown"
#endif
#ifndef GPHR_BUILD_TYPE
#define GPHR_BUILD_TYPE "unknown"
#endif
#ifndef GPHR_CXX_FLAGS
#define GPHR_CXX_FLAGS "unknown"
#endif

namespace gphr {

const char* gphrVersion() { return GPHR_VERSION_STRING; }
const char* gphrBuildType() { return GPHR_BUILD_TYPE; }
const char* gphrCxxFlags() { return GPHR_CXX_FLAGS; }

std::string toYaml(const Teuchos::ParameterList& pl) {
  std::ostringstream os;
  os << std::showpoint;  // else Teuchos warns that 1.0 would be written as the integer 1
  Teuchos::writeParameterListToYamlOStream(pl, os);
  return os.str();
}

}  // namespace gphr
