#include "gphr/timeint/SchemeResidual.hpp"

#include "gphr/timeint/Integrator.hpp"

namespace gphr {

SchemeResidual::SchemeResidual(RCP<const HamiltonianSystem> system, Teuchos::ParameterList integrator)
    : params_(validatedIntegrator(std::move(integrator))),
      backend_(system, params_.sublist("linearSolver"), true),
      scheme_(backend_,
              quadratureFor(params_.get<std::string>("scheme"), params_.get<int>("quadraturePoints"),
                            system->nonlinearTerm().polynomialDegree()),
              newtonOptionsFrom(params_)),
      R_(backend_.create()), rhs_(backend_.create()) {}

void SchemeResidual::propagateError(const Vector& y0, const Vector& y1, double dt, Vector& e) {
  scheme_.residual(y0, y1, dt, R_);
  if (age_ < 0 || age_ >= kLocalErrorMatrixAge) scheme_.assembleNewtonMatrix(y0, y1, dt), age_ = 0;
  ++age_;
  backend_.newtonMatrix()->apply(e, rhs_);  // K e0
  rhs_.update(2.0, e, -1.0, R_, -1.0);      // (2I - K) e0 - R
  const double r = rhs_.norm2();
  // to 1e-3 x the forcing relative (1e-6 by default): an estimate's digits, at a few Krylov steps
  if (r > 0.0) backend_.solveNewton(rhs_, e, 1e-3);
  else e.putScalar(0.0);
}

}  // namespace gphr
