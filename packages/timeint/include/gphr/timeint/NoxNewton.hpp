#pragma once
/// @file
/// NOX as the Newton driver of the full model's implicit steps (integrator.newtonSolver: nox).
///
/// Debian's Trilinos 13.2 has no NOX::Tpetra group, so the step's equation R(y1) = 0 is a
/// Thyra::StateFuncModelEvaluatorBase over the Thyra-Tpetra adapters, solved by NOX::Thyra::Group
/// with a Stratimikos Belos linear solver and an Ifpack2 preconditioner (registered by hand in
/// Stratimikos). The model evaluator calls AveragedGradientScheme::residual() for f and
/// AveragedGradientScheme::assembleNewtonMatrix() for W, so R and K are written once for both
/// drivers. The linearSolver section configures Belos and Ifpack2 as it does for GPHR's loop
/// (same method, tolerance, Krylov size, preconditioner and refactorisation schedule).
///
/// Status test: ||R||_2 <= newtonTolerance (converged), maxNewtonIterations reached or a non-finite
/// R (failed; SolverError naming step, time and residual). Everything of NOX (Thyra, Stratimikos,
/// Ifpack2 adapters) is in NoxNewton.cpp only: this header includes none of it.
#include <Teuchos_ParameterList.hpp>
#include <memory>

#include "gphr/timeint/AveragedGradientScheme.hpp"
#include "gphr/timeint/FullModelBackend.hpp"

namespace gphr {

/// The full model's alternative Newton driver: NOX (through Thyra) on the scheme's residual and Newton matrix.
class NoxNewtonSolver {
 public:
  /// integrator: the validated integrator list (newtonTolerance, maxNewtonIterations, jacobianReuse,
  /// linearSolver, nox). The backend must be built with ownLinearSolver = false.
  NoxNewtonSolver(AveragedGradientScheme<FullModelBackend>& scheme, FullModelBackend& backend,
                  const Teuchos::ParameterList& integrator);
  ~NoxNewtonSolver();

  /// Solve the step's equation for y1 from the guess in y1 (as AveragedGradientScheme::step).
  StepReport step(const Vector& y0, Vector& y1, double dt, long step = 0, double time = 0.0);

  /// The parameter list handed to NOX (the nox section with GPHR's defaults filled in).
  const Teuchos::ParameterList& noxParameters() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gphr
