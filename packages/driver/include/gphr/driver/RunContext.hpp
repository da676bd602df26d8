#pragma once
/// @file
/// Where a command of `gphr` runs (RunContext): its communicator and output directory. What it
/// computes is its typed options (RunOptions.hpp), handed down beside it.
#include <string>

#include "gphr/core/Types.hpp"

namespace gphr {

/// The communicator and paths of a command.
struct RunContext {
  std::string outputDir;  ///< Output directory DIR of the run.
  RCP<const Comm> comm;  ///< The communicator of the run.
  /// outputDir held an earlier gphr run's summary.json (removed at start): the report's files this
  /// run does not write are that run's and are removed when it commits. Never set for a directory
  /// gphr has not completed a run in, so no other file of the user's is touched. Rank 0 only.
  bool replacesEarlierRun = false;
  /// DIR/artifacts.h5, the cached offline results.
  std::string artifactsPath() const { return outputDir + "/artifacts.h5"; }
};

}  // namespace gphr
