#pragma once
/// @file
/// The full model's run at one parameter, the reference every reduced model's error is measured
/// against (eq:errNR): its saved physical states, its Hamiltonian at every step, its online time,
/// its Newton statistics and the drift bound of its own Hamiltonian.
#include <string>
#include <vector>

#include "gphr/evaluation/EvaluationSettings.hpp"
#include "gphr/models/Scene.hpp"

namespace gphr {

/// See the file's description.
struct FullModelReference {
  RCP<MultiVector> trajectory;      ///< physical states y = y_s + y0 at the saved steps (isSavedStep)
  std::vector<double> savedTimes;   ///< the times of the saved states
  std::vector<double> hamiltonian;  ///< H(y^j), j = 0..steps
  double tOnline = 0.0;             ///< wall seconds of the time loop (observer excluded)
  RunStats stats;                   ///< Newton and linear-solver statistics of the time loop
  double driftBound = 0.0;          ///< the bound on |H(y^j) - H(y^0)| (driftBound()); NaN where none
  /// The system's sizes: n, the phase-space dimension 2n (fullDim) and the nonlinear terms d.
  /// @{
  long n = 0, fullDim = 0, numTerms = 0;
  /// @}
  double maxStateNorm() const;      ///< max_j ||y^j|| over the saved states (the status rule's scale)
};

/// Sets the reference's sizes (n, fullDim, numTerms) from its system.
void setSizes(const HamiltonianSystem& system, FullModelReference& ref);

/// Integrates the scene's full model at parameter `mu` through the one observed time loop, with
/// progress lines every settings.progressSeconds. The full model is the reference: a Newton failure
/// or a non-finite state is a SolverError (the caller's failure), not a status. Collective.
FullModelReference runFullModel(const EvaluationSettings& settings, const Scene& scene, const std::vector<double>& mu,
                                const RCP<const Comm>& comm);

}  // namespace gphr
