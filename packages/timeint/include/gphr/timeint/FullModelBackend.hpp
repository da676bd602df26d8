#pragma once
/// @file
/// Backend of AveragedGradientScheme for the full model on Tpetra: the Newton matrix
/// K = I - dt J Hbar is assembled as a CrsMatrix on the Hessian graph (plus canonical pairs) and
/// solved with Belos (through Belos::SolverFactory) and an optional Ifpack2 preconditioner.
/// Configured by a ParameterList (validParameters() documents it). Under the NOX driver the
/// backend only assembles (ownLinearSolver = false): Stratimikos solves, with the same settings.
#include <Teuchos_ParameterList.hpp>
#include <memory>

#include "gphr/core/HamiltonianSystem.hpp"
#include "gphr/core/LocalScatter.hpp"
#include "gphr/core/Quadrature.hpp"

namespace gphr {

/// The Backend of AveragedGradientScheme for a full (Tpetra) HamiltonianSystem: Belos + Ifpack2 Newton solves.
class FullModelBackend {
 public:
  using Vector = gphr::Vector;  ///< The state vector: a distributed y.

  /// linearSolver: see validParameters(); validated here. ownLinearSolver = false: no Belos /
  /// Ifpack2 objects (solveNewton() must not be called), for a driver that solves K itself.
  FullModelBackend(RCP<const HamiltonianSystem> system, Teuchos::ParameterList linearSolver,
                   bool ownLinearSolver = true);
  ~FullModelBackend();
  /// The `linearSolver` section: keys, defaults, ranges, documentation.
  static Teuchos::ParameterList validParameters();
  /// From a validated linearSolver list, for both drivers: Ifpack2's parameters for the chosen
  /// preconditioner, and GMRES's Krylov space size ("Num Blocks").
  static Teuchos::ParameterList preconditionerParameters(const Teuchos::ParameterList& linearSolver);
  /// Whether a refresh of the configured preconditioner must initialize() it again before
  /// compute(): Ifpack2 13.2's AMESOS2 on more than one rank factors a copy of its block taken in
  /// initialize(), so compute() alone would refactor stale values.
  static bool refreshReinitializes(const Teuchos::ParameterList& linearSolver, int ranks);
  /// Krylov vectors the configured linear solver keeps.
  static int krylovVectors(const Teuchos::ParameterList& linearSolver);

  Vector create() const { return Vector(system_->map()); }  ///< A zero state on the system's map.
  void gradient(const Vector& y, Vector& g) { system_->gradient(y, g); }  ///< g = grad H(y).
  /// Always false: node by node.
  bool averagedGradient(const Vector&, const Vector&, const QuadratureRule&, Vector&) { return false; }
  void applyJ(const Vector& x, Vector& out) { system_->space().applyJ(x, out); }  ///< out = J_{2n} x.
  void beginNewtonMatrix();  ///< Starts a Newton matrix (M = I).
  /// M += scale J Hess H(y).
  void addHessian(const Vector& y, double scale) { system_->addHessian(y, scale, *newtonMatrix_, true); }
  bool addAveragedHessian(const Vector&, const Vector&, const QuadratureRule&, double) { return false; }  ///< by node
  void endNewtonMatrix();  ///< Completes the Newton matrix (fillComplete; preconditioner set-up when due).
  /// Solves M dx = rhs with Belos; returns the linear iterations. newtonRelative: the relative
  /// residual at which the solve's error equals the Newton tolerance (linearSolver.forcing).
  int solveNewton(const Vector& rhs, Vector& dx, double newtonRelative);
  /// The Newton matrix (assembled in place), and whether the last endNewtonMatrix() was one at which
  /// the preconditioner is to be refactored (every linearSolver.preconditionerRecomputeEvery).
  RCP<CrsMatrix> newtonMatrix() const { return newtonMatrix_; }
  /// Whether the next endNewtonMatrix() recomputes the preconditioner.
  bool preconditionerRefreshDue() const { return refreshDue_; }
  long newtonMatrixAssemblies() const { return assemblies_; }  ///< endNewtonMatrix() calls so far

  static void update(Vector& y, double a, const Vector& x, double b) { y.update(a, x, b); }  ///< y = a x + b y.
  /// y = a x + b y + c z.
  static void update(Vector& y, double a, const Vector& x, double b, const Vector& z, double c) {
    y.update(a, x, b, z, c);
  }
  static double norm(const Vector& x) { return x.norm2(); }  ///< ||x||_2 (collective).
  static void assign(Vector& y, const Vector& x) { Tpetra::deep_copy(y, x); }  ///< y = x.

  const HamiltonianSystem& system() const { return *system_; }  ///< The full system.

 private:
  struct Solver;  ///< Belos + Ifpack2 objects, kept out of this header (compile cost)
  RCP<const HamiltonianSystem> system_;
  RCP<CrsMatrix> newtonMatrix_;
  LocalScatter identity_;
  std::vector<Scalar> ones_;
  std::unique_ptr<Solver> solver_;  ///< null when !ownLinearSolver
  int recomputeEvery_ = 1;
  long assemblies_ = 0;
  bool refreshDue_ = false;
  bool reinitialize_ = false;  ///< refreshReinitializes() for this backend's settings and ranks
};

}  // namespace gphr
