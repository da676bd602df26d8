#include "gphr/timeint/DenseModelIntegrator.hpp"

#include <Teuchos_TimeMonitor.hpp>

#include <optional>

#include "gphr/core/ThreadTimers.hpp"

namespace gphr {

DenseModelIntegrator::DenseModelIntegrator(DenseHamiltonian& model, Teuchos::ParameterList pl, int degree)
    : params_(validatedIntegrator(std::move(pl))),
      backend_(model),
      scheme_(backend_, quadratureFor(params_.get<std::string>("scheme"), params_.get<int>("quadraturePoints"), degree),
              newtonOptionsFrom(params_)) {}

RunStats DenseModelIntegrator::run(DenseVector& z, double dt, long steps, const StepObserver<DenseVector>& observer) {
  std::optional<Teuchos::TimeMonitor> tm;  // not on a query worker thread (ThreadTimers.hpp)
  if (processTimersOn()) tm.emplace(*Teuchos::TimeMonitor::getNewCounter("gphr: dense model time stepping"));
  return integrate(scheme_, backend_, z, dt, steps, observer, scheme_.options().predictorOrder);
}

}  // namespace gphr
