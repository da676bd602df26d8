#pragma once
/// @file
/// The Galerkin ROM stage of `gphr run`: the ROM at the test parameter for every k, evaluated
/// against the full model (errors eq:errNR at the saved steps).
#include "gphr/driver/FomStage.hpp"
#include "gphr/driver/OfflineStages.hpp"

namespace gphr {

/// Galerkin ROM at the test parameter for every k; its runs are appended to stages.runs.
void runRom(const RunOptions& options, const FomResult& fom, RomStages& stages);

}  // namespace gphr
