#pragma once
/// @file
/// What `gphr run` prints on stdout by default: one line per evaluated model (method, k, m,
/// status, E_L2, online seconds, speed-up over the full model's online time) and where the report
/// is; summary.json and report.md hold the rest.
#include <string>

#include "gphr/driver/FomStage.hpp"
#include "gphr/driver/OfflineStages.hpp"

namespace gphr {

/// The default stdout of `gphr run`: the table of runs (the file's description) and where the report is.
std::string runTable(const RunContext& ctx, const RunOptions& options, const FomResult& fom, const RomStages* rom);

}  // namespace gphr
