#pragma once
// The full model's time integrator: FullModelBackend + AveragedGradientScheme, configured by a
// validated `integrator` ParameterList (integratorValidParameters()).
#include "gphr/timeint/FullModelBackend.hpp"
#include "gphr/timeint/Integrator.hpp"

namespace gphr {

class FullModelIntegrator {
 public:
  FullModelIntegrator(RCP<const HamiltonianSystem> system, Teuchos::ParameterList integrator);

  // Advance y (in place) by `steps` steps of size dt; the observer sees every state.
  RunStats run(Vector& y, double dt, long steps, const StepObserver<Vector>& observer = {},
               double t0 = 0.0, long firstStep = 0);
  AveragedGradientScheme<FullModelBackend>& scheme() { return scheme_; }
  FullModelBackend& backend() { return backend_; }
  const Teuchos::ParameterList& parameters() const { return params_; }

 private:
  static Teuchos::ParameterList validated(Teuchos::ParameterList pl);
  Teuchos::ParameterList params_;
  FullModelBackend backend_;
  AveragedGradientScheme<FullModelBackend> scheme_;
};

}  // namespace gphr
