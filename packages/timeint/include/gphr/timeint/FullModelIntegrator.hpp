#pragma once
/// @file
/// The full model's time integrator: FullModelBackend + AveragedGradientScheme, configured by a
/// validated `integrator` ParameterList (integratorValidParameters()). The Newton driver of each
/// step is GPHR's own loop (default) or NOX (integrator.newtonSolver: nox, NoxNewtonSolver).
#include <memory>

#include "gphr/timeint/FullModelBackend.hpp"
#include "gphr/timeint/Integrator.hpp"
#include "gphr/timeint/NoxNewton.hpp"

namespace gphr {

/// IMR / AVF time integration of a full (Tpetra) HamiltonianSystem, with GPHR's Newton loop or NOX.
class FullModelIntegrator {
 public:
  /// Integrator of `system` with the `integrator` section of the config (validated).
  FullModelIntegrator(RCP<const HamiltonianSystem> system, Teuchos::ParameterList integrator);
  ~FullModelIntegrator();

  /// Advance y (in place) by `steps` steps of size dt; the observer sees every state.
  RunStats run(Vector& y, double dt, long steps, const StepObserver<Vector>& observer = {},
               double t0 = 0.0, long firstStep = 0);
  /// One step from y0, starting from the guess in y1, with the configured driver.
  StepReport step(const Vector& y0, Vector& y1, double dt, long stepNo = 0, double time = 0.0);
  AveragedGradientScheme<FullModelBackend>& scheme() { return scheme_; }  ///< The time scheme.
  FullModelBackend& backend() { return backend_; }  ///< The Tpetra backend.
  const Teuchos::ParameterList& parameters() const { return params_; }  ///< The validated integrator section.
  bool usesNox() const { return nox_ != nullptr; }  ///< Whether Newton runs through NOX.
  const NoxNewtonSolver* nox() const { return nox_.get(); }  ///< null under GPHR's loop

 private:
  Teuchos::ParameterList params_;
  FullModelBackend backend_;
  AveragedGradientScheme<FullModelBackend> scheme_;
  std::unique_ptr<NoxNewtonSolver> nox_;  ///< null: GPHR's loop (scheme_.step)
};

}  // namespace gphr
