#include "gphr/timeint/FullModelIntegrator.hpp"

#include <Teuchos_TimeMonitor.hpp>


namespace gphr {

FullModelIntegrator::FullModelIntegrator(RCP<const HamiltonianSystem> system, Teuchos::ParameterList pl)
    : params_(validatedIntegrator(std::move(pl))),
      backend_(system, params_.sublist("linearSolver"), params_.get<std::string>("newtonSolver") == "gphr"),
      scheme_(backend_,
              quadratureFor(params_.get<std::string>("scheme"), params_.get<int>("quadraturePoints"),
                            system->nonlinearTerm().polynomialDegree()),
              newtonOptionsFrom(params_)) {
  if (params_.get<std::string>("newtonSolver") == "nox") nox_.reset(new NoxNewtonSolver(scheme_, backend_, params_));
}

FullModelIntegrator::~FullModelIntegrator() = default;

StepReport FullModelIntegrator::step(const Vector& y0, Vector& y1, double dt, long stepNo, double time) {
  return nox_ ? nox_->step(y0, y1, dt, stepNo, time) : scheme_.step(y0, y1, dt, stepNo, time);
}

RunStats FullModelIntegrator::run(Vector& y, double dt, long steps, const StepObserver<Vector>& observer,
                                  double t0, long firstStep) {
  Teuchos::TimeMonitor tm(*Teuchos::TimeMonitor::getNewCounter("gphr: full model time stepping"));
  return integrate(*this, backend_, y, dt, steps, observer, scheme_.options().predictorOrder, t0, firstStep);
}

}  // namespace gphr
