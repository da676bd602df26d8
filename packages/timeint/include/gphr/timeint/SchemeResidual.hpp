#pragma once
/// @file
/// The full model's time-scheme residual at a pair of given states, without a Newton solve:
///   R(y0, y1) = y1 - y0 - dt J sum_q w_q grad H(y0 + s_q (y1 - y0))
/// of the one scheme (AveragedGradientScheme: IMR or AVF by the integrator section), and the
/// linearised error equation it drives. Along the lift of a reduced trajectory, whose steps solve
/// the full scheme only up to R, it carries the lift's error from step to step: the error
/// indicator of the evaluation library (doc/error-estimate.md).
#include <Teuchos_ParameterList.hpp>

#include "gphr/timeint/AveragedGradientScheme.hpp"
#include "gphr/timeint/FullModelBackend.hpp"

namespace gphr {

/// See the file's description.
class SchemeResidual {
 public:
  /// The scheme of the (validated or partial) `integrator` section for `system`.
  SchemeResidual(RCP<const HamiltonianSystem> system, Teuchos::ParameterList integrator);
  /// One step of the linearised error equation along a trajectory y that satisfies the scheme
  /// only up to R: the full model's solution x = y + e solves R(x0, x1) = 0, so to first order in e
  ///   K e1 = (2I - K) e0 - R(y0, y1),   K = I - dt J sum_q w_q s_q Hess H(y_q)   (the Newton matrix),
  /// with 2I - K standing for I + dt J sum_q w_q (1 - s_q) Hess H(y_q): equal for IMR, and for a
  /// symmetric rule (AVF's) where Hess H is constant, to O(dt |y1 - y0|) otherwise. For a quadratic
  /// H the step is exact (K is then constant, so its lag costs nothing either). e holds e0 on
  /// entry, e1 on exit. K is assembled at the first call and again every kLocalErrorMatrixAge
  /// calls (lagged, as the full model's Newton matrix); the solve is the integrator's linear
  /// solver, to 1e-3 x its forcing relative. Collective.
  void propagateError(const Vector& y0, const Vector& y1, double dt, Vector& e);
  static constexpr int kLocalErrorMatrixAge = 20;  ///< propagateError calls between assemblies of K

 private:
  Teuchos::ParameterList params_;  ///< the validated integrator section (before the backend: it configures it)
  FullModelBackend backend_;
  AveragedGradientScheme<FullModelBackend> scheme_;
  Vector R_, rhs_;
  int age_ = -1;
};

}  // namespace gphr
