#pragma once
/// @file
/// The speed-accuracy part of the report: runs.csv (one row per evaluated model),
/// report.md (tables, speed-ups measured in this run, the cheapest (k, m) per error level) and the
/// gnuplot figures of the paper: error vs m with the ROM's error as a line
/// (fig:2dsw_errors_avf_imr), error vs online time (the Pareto front), the Hamiltonian error terms
/// over time (fig:2dsw_hamcons) and singular values of both PODs (fig:singvalues); the fields are
/// FieldPictures.hpp's. All written on rank 0 to the
/// given (temporary) paths; a missing gnuplot skips the figures only.
#include <map>
#include <string>

#include "gphr/driver/FomStage.hpp"
#include "gphr/driver/OfflineStages.hpp"
#include "gphr/driver/RunContext.hpp"

namespace gphr {

/// Root only. paths: "runs.csv", "error_vs_m.png", "pareto.png", "hamiltonian_terms.png",
/// "deim_singular_values.csv" ... -> temporary file names. Returns the names of the files written.
/// report.md comes after every picture (writeHyperReportMd), so that it names those drawn.
std::vector<std::string> writeHyperReport(const RunOptions& options, const FomResult& fom, const RomStages& st,
                                          const std::map<std::string, std::string>& paths,
                                          bool plots);

/// Root only: report.md at `path`, naming `figures` (the pictures drawn, in order) and the field
/// picture's note where none was drawn (`fieldNote`, e.g. why).
void writeHyperReportMd(const RunContext& ctx, const RunOptions& options, const FomResult& fom, const RomStages& st,
                        const std::string& path, const std::vector<std::string>& figures, const std::string& fieldNote);

}  // namespace gphr
