#pragma once
/// @file
/// The full-order-model stage of `gphr run`: integrate the scene's full model at the test
/// parameter, keep every saveEvery-th (physical) state and the Hamiltonian at every step.
#include <Teuchos_ParameterList.hpp>
#include <memory>
#include <string>
#include <vector>

#include "gphr/driver/RunMetrics.hpp"
#include "gphr/models/Scene.hpp"
#include "gphr/online/TimeLoop.hpp"

namespace gphr {

class FieldStates;

/// The full model's results at the test parameter: saved states, Hamiltonian history, online time.
struct FomResult {
  RCP<MultiVector> trajectory;  ///< physical states y = y_s + y0, every saveEvery-th step and the last
  std::vector<double> savedTimes;  ///< Times of the saved states.
  std::vector<double> hamiltonian;  ///< H(y^j), j = 0..steps
  double tOnline = 0.0;             ///< wall seconds of the time loop (observer excluded)
  RunMetrics metrics;               ///< the figures of its "runs" entry of summary.json
  /// The reduced runs' lifted states the field outputs show, collected as the runs are evaluated
  /// against this full model (FieldModels.hpp); null when no field output is asked for.
  std::shared_ptr<FieldStates> fieldStates;
};

/// The steps whose states are kept (every saveEvery-th and the last), and the largest
/// |H_j - H0| of a Hamiltonian history: shared by the full and reduced model stages.
inline bool isSavedStep(long j, long steps, long saveEvery) { return j % saveEvery == 0 || j == steps; }
/// The largest |H_j - H0| of a Hamiltonian history.
double maxDeviation(const std::vector<double>& H, double H0);
/// The run's bound on the drift of its own Hamiltonian (RunStats::driftBound) where the
/// integrator's rule is exact for G of polynomial degree `degree` (quadratureIsExact); NaN (null
/// in summary.json) where it is not, or the degree is unknown.
double driftBound(const Teuchos::ParameterList& integrator, int degree, const RunStats& stats);

/// What an evaluation against the full model runs, for the full model and every reduced one: the
/// time loop (dt, steps, the integrator section), the saved steps, the timing repeats of the
/// reduced models, the full model's progress lines and whether the system is shifted. `gphr run`
/// takes it from its config (evaluationSettingsFrom), `gphr validate` from the model file and the
/// test point.
struct EvaluationSettings {
  SimulationSettings time;           ///< dt, steps and the integrator section (the degree is the model's)
  long saveEvery = 1;                ///< keep every saveEvery-th state (and the last)
  int onlineRepeats = 1;             ///< timing repeats of a reduced model's time loop (pipeline.onlineRepeats)
  double onlineRepeatSeconds = 60.0; ///< their total time at most (pipeline.onlineRepeatSeconds)
  double progressSeconds = 2.0;      ///< between the full model's progress lines (0: none)
  bool shift = true;                 ///< integrate the shifted system (scene.shift)
  /// output.fieldModels when the run draws or writes fields (output.plots or output.xdmf): the
  /// full model's result then collects the field states (FomResult::fieldStates); empty: none
  std::vector<std::string> fieldModels;
};

/// The evaluation settings of a validated `gphr run` configuration.
EvaluationSettings evaluationSettingsFrom(const Teuchos::ParameterList& cfg);

/// Integrates the scene's full model at parameter `mu` (see the file's description).
FomResult runFullModel(const EvaluationSettings& settings, const Scene& scene, const std::vector<double>& mu,
                       const RCP<const Comm>& comm);

}  // namespace gphr
