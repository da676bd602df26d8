#pragma once
/// @file
/// The context every stage of `gphr run` shares (RunContext).
#include <Teuchos_ParameterList.hpp>
#include <memory>
#include <string>
#include <vector>

#include "gphr/models/Scene.hpp"

namespace gphr {

/// What every stage of `gphr run` needs: the validated config, the scene, the test parameter.
struct RunContext {
  std::string outputDir;  ///< Output directory DIR of the run.
  Teuchos::ParameterList config;  ///< validated
  std::shared_ptr<Scene> scene;  ///< The scene of the config.
  std::vector<double> mu;  ///< test parameter
  RCP<const Comm> comm;  ///< The communicator of the run.
  /// outputDir held an earlier gphr run's summary.json (removed at start): the report's files this
  /// run does not write are that run's and are removed when it commits. Never set for a directory
  /// gphr has not completed a run in, so no other file of the user's is touched. Rank 0 only.
  bool replacesEarlierRun = false;
  /// DIR/artifacts.h5, the cached offline results.
  std::string artifactsPath() const { return outputDir + "/artifacts.h5"; }
};

}  // namespace gphr
