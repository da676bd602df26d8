#pragma once
/// @file
/// The calibration of the online error indicator (hyper/ErrorIndicator.hpp, doc/error-estimate.md)
/// of every model of a reduced-model file, where the build knows the true error: at each training
/// parameter the model is run as a query runs it (from the file's data, interpolated set-up), its
/// indicator eta taken, and its E_L2 (eq:errNR) measured against the training trajectory at the
/// snapshots; E_L2 ~ scale eta^exponent is fitted per model over those points
/// (fitIndicatorCalibration) and stored with the model.
#include <map>
#include <vector>

#include "gphr/hyper/ReducedModelFile.hpp"
#include "gphr/models/Scene.hpp"
#include "gphr/offline/Training.hpp"

namespace gphr {

/// One training point of one model: its indicator and true error (NaN where the run failed).
struct CalibrationPoint {
  std::vector<double> parameter;  ///< mu
  double indicator = 0.0;         ///< eta
  double error = 0.0;             ///< E_L2 against the training trajectory
};

/// Every model of `data` whose k has indicator rows and a basis in `bases`, run as a query at each
/// parameter of `reference` (a training result: shifted states every `snapshotEvery`-th of `steps`
/// steps of size dt), with its indicator and its E_L2 against that trajectory (NaN where the run
/// failed). The calibration's measure; also the greedy build's confirmation at fresh points. Collective.
std::map<std::string, std::vector<CalibrationPoint>> measureModelErrors(
    const ReducedModelData& data, const Scene& scene, const HamiltonianSystem& like,
    const std::map<int, RCP<const MultiVector>>& bases, const TrainingResult& reference, long snapshotEvery,
    double dt, long steps);

/// Calibrates every model of `data` whose k has indicator rows (see the file's description):
/// bases[k] is A of k on `like`'s map (the build's shifted instance); the training's snapshots
/// are the shifted states every `snapshotEvery`-th of `steps` steps of size dt. Returns the points
/// per model key. gp-adeim models are calibrated where their k's basis is given. Collective.
std::map<std::string, std::vector<CalibrationPoint>> calibrateErrorIndicators(
    ReducedModelData& data, const Scene& scene, const HamiltonianSystem& like,
    const std::map<int, RCP<const MultiVector>>& bases, const TrainingResult& training, long snapshotEvery,
    double dt, long steps);

}  // namespace gphr
