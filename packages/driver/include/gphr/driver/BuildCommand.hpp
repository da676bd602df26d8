#pragma once
/// @file
/// `gphr build` (BuildCommand.cpp).
#include <string>

#include "gphr/core/Types.hpp"

namespace gphr {

/// `gphr build`: the offline stages of the config at `configPath` -> the reduced-model file `modelPath`.
/// targetError > 0 (--target-error; else build.targetError): greedy training to it (GreedyTraining.hpp).
int runBuild(const std::string& configPath, const std::string& modelPath, const std::string& artifactsDir,
             const RCP<const Comm>& comm, double targetError = 0.0);

}  // namespace gphr
