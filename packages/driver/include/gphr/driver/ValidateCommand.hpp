#pragma once
/// @file
/// `gphr validate` (ValidateCommand.cpp).
#include <string>

#include "gphr/core/Types.hpp"

namespace gphr {

/// `gphr validate`: the model file's models against the full model at the test parameters of `testsPath`.
int runValidate(const std::string& modelPath, const std::string& testsPath, const std::string& outputDir,
                const RCP<const Comm>& comm);

}  // namespace gphr
