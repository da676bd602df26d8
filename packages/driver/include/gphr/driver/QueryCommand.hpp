#pragma once
/// @file
/// `gphr query` (QueryCommand.cpp).
#include <string>

#include "gphr/core/Types.hpp"

namespace gphr {

/// `gphr query`: the model file's models at the parameters of `queriesPath`, results in `outputDir`.
int runQuery(const std::string& modelPath, const std::string& queriesPath, const std::string& outputDir,
             const RCP<const Comm>& comm);

}  // namespace gphr
