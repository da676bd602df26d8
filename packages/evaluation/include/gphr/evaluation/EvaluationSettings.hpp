#pragma once
/// @file
/// What an evaluation against the full model runs, for the full model and every reduced one: the
/// time loop (dt, steps, the integrator section), the saved steps (where the error eq:errNR is
/// measured), the timing repeats of the reduced models, the full model's progress lines and
/// whether the system is shifted. `gphr run` takes it from its config, `gphr validate` from the
/// model file and the test point, an embedding code sets it.
#include <vector>

#include "gphr/online/TimeLoop.hpp"

namespace gphr {

/// See the file's description.
struct EvaluationSettings {
  SimulationSettings time;            ///< dt, steps and the integrator section (the degree is the model's)
  long saveEvery = 1;                 ///< keep every saveEvery-th state (and the last): the error's steps
  int onlineRepeats = 1;              ///< timing repeats of a reduced model's time loop (its fastest is t_online)
  double onlineRepeatSeconds = 60.0;  ///< their total time at most
  double progressSeconds = 0.0;       ///< between the full model's progress lines on stderr (0: none)
  bool shift = true;                  ///< integrate the shifted system (Scene::instantiate)
  /// Estimate each reduced run's E_L2 from the full scheme's residual at its lift (ReducedEvaluation::
  /// errorEstimate): per step, one residual of the full scheme and one linear solve with its
  /// Newton matrix, after the timed run.
  bool errorIndicator = true;
};

/// The steps whose states are kept: every saveEvery-th and the last.
inline bool isSavedStep(long j, long steps, long saveEvery) { return j % saveEvery == 0 || j == steps; }
/// The number of saved states of a run of `steps` steps.
inline long numSavedStates(long steps, long saveEvery) { return steps / saveEvery + 1 + (steps % saveEvery != 0); }
/// The largest |H_j - H0| of a Hamiltonian history.
double maxDeviation(const std::vector<double>& H, double H0);
/// A run's bound on the drift of its own Hamiltonian (RunStats::driftBound) where the integrator's
/// rule is exact for a nonlinear term of polynomial degree `degree` (quadratureIsExact); NaN where
/// it is not, or the degree is unknown (0).
double driftBound(const SimulationSettings& time, int degree, const RunStats& stats);

}  // namespace gphr
