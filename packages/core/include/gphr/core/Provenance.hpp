#pragma once
/// @file
/// What GPHR stores as provenance beside its results (model files, artifacts, summary.json): the
/// version of the build and configuration text as YAML. In core so that every stage that writes
/// a file states the same version, whichever library it lives in.
#include <Teuchos_ParameterList.hpp>
#include <string>

namespace gphr {

/// The gphr version: the project version and git describe of the source tree at configure time.
const char* gphrVersion();
const char* gphrBuildType();  ///< The CMake build type of this build.
const char* gphrCxxFlags();   ///< The C++ flags of that build type.

/// A ParameterList as YAML text: stored as provenance and compared as a cache key.
std::string toYaml(const Teuchos::ParameterList& pl);

}  // namespace gphr
