#pragma once
/// @file
/// Backend of AveragedGradientScheme for small, replicated (dense) Hamiltonian systems
/// z' = J_{2k} grad H(z): the Galerkin reduced model and the hyper-reduced models. The Newton
/// matrix K = I - dt J Hbar is formed densely (2k x 2k) and LU-factored with Teuchos::LAPACK.
#include <Teuchos_LAPACK.hpp>
#include <vector>

#include "gphr/core/DenseHamiltonian.hpp"

namespace gphr {

/// The Backend of AveragedGradientScheme for a DenseHamiltonian: dense Newton matrix and LU (LAPACK).
class DenseBackend {
 public:
  using Vector = DenseVector;  ///< The state vector: a small dense z.
  explicit DenseBackend(DenseHamiltonian& model);  ///< Backend of `model` (kept by reference).

  Vector create() const { return Vector(model_.dim()); }  ///< A zero state of size 2k.
  void gradient(const Vector& z, Vector& g) { model_.gradient(z, g); }  ///< g = grad H(z).
  /// gbar of (*) from the model at once, if it can (false: the scheme loops over nodes).
  bool averagedGradient(const Vector& z0, const Vector& z1, const QuadratureRule& rule, Vector& gbar) {
    return model_.averagedGradient(z0, z1, rule, gbar);
  }
  void applyJ(const Vector& x, Vector& out) { applyCanonicalJ(x, out); }  ///< out = J_{2k} x.
  void beginNewtonMatrix() { hbar_.putScalar(0.0); }  ///< Starts a Newton matrix (hbar = 0).
  void addHessian(const Vector& z, double scale) { model_.addHessian(z, scale, hbar_); }  ///< hbar += scale Hess H(z).
  /// hbar += scale sum_q w_q s_q Hess H(z_q) from the model at once, if it can (false: node by node).
  bool addAveragedHessian(const Vector& z0, const Vector& z1, const QuadratureRule& rule, double scale) {
    return model_.addAveragedHessian(z0, z1, rule, scale, hbar_);
  }
  void endNewtonMatrix();  ///< K = I + J hbar (hbar holds -dt Hbar), then LU
  /// Solves K dx = rhs with the LU of endNewtonMatrix() (exact: the Newton tolerance's share is
  /// not used); returns 0 (linear iterations).
  int solveNewton(const Vector& rhs, Vector& dx, double newtonRelative = 0.0);
  /// Newton matrices assembled and LU-factored so far (endNewtonMatrix() calls).
  long newtonMatrixAssemblies() const { return assemblies_; }

  static void update(Vector& y, double a, const Vector& x, double b);  ///< y = a x + b y.
  /// y = a x + b y + c z.
  static void update(Vector& y, double a, const Vector& x, double b, const Vector& z, double c);
  static double norm(const Vector& x) { return x.normFrobenius(); }  ///< ||x||_2.
  static void assign(Vector& y, const Vector& x) { y.assign(x); }  ///< y = x.

 private:
  DenseHamiltonian& model_;
  DenseMatrix hbar_, K_;
  std::vector<int> pivots_;
  Teuchos::LAPACK<int, double> lapack_;
  long assemblies_ = 0;
};

}  // namespace gphr
