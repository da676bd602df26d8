#pragma once
/// @file
/// A reduced or hyper-reduced model's run against a full-model reference: integrate z from 0 (the
/// shifted initial state) through the one observed time loop, lift y = y0 + A z and measure the
/// paper's error eq:errNR at the saved steps, the Hamiltonian of the lift at every step and the
/// model's own Hamiltonian; then decide its status (RunStatus.hpp): a Newton failure or a non-finite
/// state or H is `diverged`, a run whose lift leaves the full model's range is `unbounded`. Either
/// is a result, not an error: E_L2 and the times are reported for every run that reached the end.
#include <limits>
#include <string>
#include <vector>

#include "gphr/core/DenseHamiltonian.hpp"
#include "gphr/core/HamiltonianSystem.hpp"
#include "gphr/evaluation/FullModelReference.hpp"
#include "gphr/online/TimeLoop.hpp"

namespace gphr {

/// How one reduced run is evaluated.
struct ReducedRunOptions {
  bool hasHamiltonian = true;  ///< observe the model's own H (MethodInfo::hasHamiltonian(): not the DEIM baselines)
  bool keepStates = false;     ///< keep the lifted physical states at the saved steps (ReducedEvaluation::states)
  StepHook adapt;              ///< after every step, in online time: GP-ADEIM's update (adeimUpdateHook); none: repeatable
  std::string label;           ///< the run's name in progress lines (core/Progress.hpp); empty: "reduced model"
};

/// The figures and histories of one reduced run (see the file's description).
struct ReducedEvaluation {
  static constexpr double kNotMeasured = std::numeric_limits<double>::quiet_NaN();  ///< a figure of a run never made
  std::vector<double> hamiltonian;       ///< H(y0 + A z^j) per step: the true Hamiltonian of the lift
  std::vector<double> modelHamiltonian;  ///< the model's own H_r / H_hr per step (empty without one)
  std::vector<double> errors;            ///< ||y^j - (y0 + A z^j)|| at the saved steps
  std::vector<double> stateNorms;        ///< ||y0 + A z^j|| per step
  std::vector<RCP<Vector>> states;       ///< the lifted states at the saved steps, where keepStates
  /// ||e^j||, j = 1..N: the error of the lift estimated by the full scheme's linearised error
  /// equation, driven by the scheme's residual at the lift (SchemeResidual::propagateError), where
  /// EvaluationSettings::errorIndicator
  std::vector<double> estimatedErrors;
  /// E_L2 (eq:errNR, over the saved steps) and the relative error at the last step; NaN unless it reached the end.
  /// @{
  double eL2 = kNotMeasured, eFinal = kNotMeasured;
  /// @}
  /// The estimate of eL2 that needs no reference: eq:errNR with the errors at the saved steps
  /// replaced by estimatedErrors and the reference's norms by the lift's (doc/error-estimate.md
  /// says what it is and where it stops holding); NaN unless it reached the end with
  /// EvaluationSettings::errorIndicator, and where the error equation's linear solve failed (a
  /// lift far outside the full model's range).
  double errorEstimate = kNotMeasured;
  /// The lift's Hamiltonian against the reference's: max_j |H(y0 + A z^j) - H(y^0)|, the same over
  /// |H(y^0)| (not divided where H(y^0) = 0) and |H(y^N) - H(y0 + A z^N)| at the last step; NaN
  /// unless it reached the end.
  /// @{
  double hamiltonianErrorMax = kNotMeasured, hamiltonianErrorMaxRelative = kNotMeasured,
         hamiltonianErrorFinal = kNotMeasured;
  /// @}
  /// max_j |H_hr(z^j) - H_hr(z^0)|: the model's conservation of its own Hamiltonian (GP-ADEIM:
  /// over each interval between two updates, set by its caller); NaN without one or unless it
  /// reached the end.
  double modelHamiltonianDrift = kNotMeasured;
  double tOnline = kNotMeasured;     ///< the fastest of its timed runs (wall seconds)
  std::vector<double> onlineTimes;   ///< every timed run's seconds (EvaluationSettings::onlineRepeats)
  RunStats stats;                    ///< Newton statistics of the observed run
  double driftBound = kNotMeasured;  ///< the bound on its own H's drift (driftBound()); NaN where none
  bool ok = true;                    ///< false: diverged (or, for a run never made, unavailable)
  bool available = true;             ///< false: not run, the offline data cannot support its (k, m)
  long lastStep = 0;                 ///< the last step observed
  std::string divergedReason;        ///< why it diverged (where !ok)
  long unboundedAt = -1;             ///< >= 0: ran to the end, but its lift left the full model's range at this step
  std::string unboundedReason;       ///< which bound it passed, with the figures
  /// ok | unbounded | diverged | unavailable
  RunStatus status() const { return runStatus(ok, available, unboundedAt); }
  bool bounded() const { return ok && unboundedAt < 0; }  ///< status ok
};

/// Evaluates `model` (of reduced size A's columns) against `reference` on the (shifted) `system`
/// whose basis is A (see the file's description). Collective over A's communicator: the lift and,
/// for a ROM, the model's own operators.
ReducedEvaluation evaluateReducedModel(const EvaluationSettings& settings, const FullModelReference& reference,
                                       const HamiltonianSystem& system, const MultiVector& A, DenseHamiltonian& model,
                                       const ReducedRunOptions& options = {});

}  // namespace gphr
