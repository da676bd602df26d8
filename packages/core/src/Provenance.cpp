#include "gphr/core/Provenance.hpp"

#include <Teuchos_YamlParameterListCoreHelpers.hpp>
#include <sstream>

#include "GphrVersion.h"  // GPHR_VERSION_STRING, written at build time (cmake/GPHRGitDescribe.cmake)

// Set by packages/core/CMakeLists.txt at configure time (they change only with a new configuration).
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
