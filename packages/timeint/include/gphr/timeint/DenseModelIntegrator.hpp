#pragma once
// Time integrator of small dense Hamiltonian systems (reduced, hyper-reduced): DenseBackend +
// the same AveragedGradientScheme as the full model, configured by the same validated
// `integrator` ParameterList (its linearSolver section does not apply: solves are dense LU).
#include "gphr/timeint/DenseBackend.hpp"
#include "gphr/timeint/Integrator.hpp"

namespace gphr {

class DenseModelIntegrator {
 public:
  // degree: polynomial degree of the model's G (for the AVF quadrature).
  DenseModelIntegrator(DenseHamiltonian& model, Teuchos::ParameterList integrator, int degree);
  RunStats run(DenseVector& z, double dt, long steps, const StepObserver<DenseVector>& observer = {});
  AveragedGradientScheme<DenseBackend>& scheme() { return scheme_; }
  const DenseBackend& backend() const { return backend_; }

 private:
  static Teuchos::ParameterList validated(Teuchos::ParameterList pl);
  Teuchos::ParameterList params_;
  DenseBackend backend_;
  AveragedGradientScheme<DenseBackend> scheme_;
};

}  // namespace gphr
