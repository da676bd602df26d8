#pragma once
/// @file
/// Time integrator of small dense Hamiltonian systems (reduced, hyper-reduced): DenseBackend +
/// the same AveragedGradientScheme as the full model, configured by the same validated
/// `integrator` ParameterList (its linearSolver section does not apply: solves are dense LU).
#include "gphr/timeint/DenseBackend.hpp"
#include "gphr/timeint/Integrator.hpp"

namespace gphr {

/// IMR / AVF time integration of a reduced or hyper-reduced model (a DenseHamiltonian) with dense Newton.
class DenseModelIntegrator {
 public:
  /// degree: polynomial degree of the model's G (for the AVF quadrature).
  DenseModelIntegrator(DenseHamiltonian& model, Teuchos::ParameterList integrator, int degree);
  /// Integrates z over `steps` steps of size dt, calling `observer` after each; returns the run's statistics.
  RunStats run(DenseVector& z, double dt, long steps, const StepObserver<DenseVector>& observer = {});
  AveragedGradientScheme<DenseBackend>& scheme() { return scheme_; }  ///< The time scheme.
  const DenseBackend& backend() const { return backend_; }  ///< The dense backend (Newton matrix counts).

 private:
  Teuchos::ParameterList params_;
  DenseBackend backend_;
  AveragedGradientScheme<DenseBackend> scheme_;
};

}  // namespace gphr
