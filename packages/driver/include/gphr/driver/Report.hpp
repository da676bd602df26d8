#pragma once
/// @file
/// Outputs of `gphr run`: DIR/artifacts.h5, DIR/summary.json, DIR/fom_history.csv and, with
/// gnuplot, DIR/hamiltonian.png. Each is written to a temporary name and renamed only when every
/// output is complete, so an interrupted or failed run leaves no half-written file.
#include <string>

#include "gphr/driver/FomStage.hpp"
#include "gphr/driver/OfflineStages.hpp"
#include "gphr/driver/RunContext.hpp"

namespace gphr {

/// Write all outputs of the run; returns the summary JSON text.
std::string writeReport(const RunContext& ctx, const RunOptions& options, const FomResult& fom, const RomStages* rom);
/// Machine description for benchmarks and summaries (host, cores, ranks, Trilinos, compiler).
JsonObject machineInfo(const RCP<const Comm>& comm);

}  // namespace gphr
