#pragma once
/// @file
/// `gphr query` (QueryCommand.cpp).
#include <string>

#include "gphr/core/Types.hpp"

namespace gphr {

/// `gphr query`: the model file's models at the parameters of `queriesPath`, results in `outputDir`;
/// each rank's queries on `threads` threads (0: defaultQueryThreads, QueryThreads.hpp).
int runQuery(const std::string& modelPath, const std::string& queriesPath, const std::string& outputDir,
             const RCP<const Comm>& comm, int threads = 0);

}  // namespace gphr
