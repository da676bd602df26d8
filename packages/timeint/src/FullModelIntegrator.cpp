#include "gphr/timeint/FullModelIntegrator.hpp"

#include <Teuchos_TimeMonitor.hpp>

#include "gphr/core/ParameterValidation.hpp"

namespace gphr {

Teuchos::ParameterList FullModelIntegrator::validated(Teuchos::ParameterList pl) {
  validateParameters(pl, integratorValidParameters(), "integrator");
  return pl;
}

FullModelIntegrator::FullModelIntegrator(RCP<const HamiltonianSystem> system, Teuchos::ParameterList pl)
    : params_(validated(std::move(pl))),
      backend_(system, params_.sublist("linearSolver")),
      scheme_(backend_,
              quadratureFor(params_.get<std::string>("scheme"), params_.get<int>("quadraturePoints"),
                            system->nonlinearTerm().polynomialDegree()),
              newtonOptionsFrom(params_)) {}

RunStats FullModelIntegrator::run(Vector& y, double dt, long steps, const StepObserver<Vector>& observer,
                                  double t0, long firstStep) {
  Teuchos::TimeMonitor tm(*Teuchos::TimeMonitor::getNewCounter("gphr: full model time stepping"));
  return integrate(scheme_, backend_, y, dt, steps, observer, t0, firstStep);
}

}  // namespace gphr
