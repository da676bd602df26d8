#pragma once
/// @file
/// The Hamiltonian contract (paper eq:Ham with eq:decomp):
///   H(y) = 1/2 y^T L y + y^T f + c + N(y),   N(y) = v^T G(y),   y' = J_{2n} grad H(y),
/// L symmetric (a Tpetra::CrsMatrix on the state map), N given by a NonlinearTerm's row kernel.
#include "gphr/core/NonlinearAssembly.hpp"
#include "gphr/core/PhaseSpace.hpp"

namespace gphr {

/// A full-order Hamiltonian system H(y) = 1/2 y^T L y + y^T f + c + v^T G(y) on a phase space (the file's contract).
class HamiltonianSystem {
 public:
  /// The system with linear part L, linear force f, constant c and nonlinearity N = v^T G on `space`.
  HamiltonianSystem(RCP<const PhaseSpace> space, RCP<const CrsMatrix> L, RCP<const Vector> f,
                    Scalar c, RCP<const NonlinearTerm> nonlinear);

  /// The shifted system of paper Sec.\ 3.3 (eq:shiftH): state y_s = y - y0 and
  /// H_s(y_s) = H(y_s + y0) = 1/2 y_s^T L y_s + y_s^T (f + L y0) + H(y0) + v^T (G(y_s + y0) - G(y0)).
  /// Its initial state is 0 and G_s(y0) = 0, the hypotheses of prop:ham_cons.
  RCP<HamiltonianSystem> shifted(const Vector& y0) const;
  /// The accumulated shift (null if unshifted): the physical state is y_s + reference().
  RCP<const Vector> reference() const { return assembly_.reference(); }

  const PhaseSpace& space() const { return *space_; }  ///< The phase space R^{2n}.
  const RCP<const PhaseSpace>& spacePtr() const { return space_; }  ///< The phase space, shared.
  const RCP<const Map>& map() const { return space_->map(); }  ///< The state map (2n entries).
  const CrsMatrix& linearPart() const { return *L_; }  ///< L, the symmetric linear part.
  const Vector& linearForce() const { return *f_; }  ///< f, the linear force.
  Scalar constant() const { return c_; }  ///< c, the constant of H.
  const NonlinearTerm& nonlinearTerm() const { return assembly_.term(); }  ///< The decomposed nonlinearity N = v^T G.
  RCP<const NonlinearTerm> nonlinearTermPtr() const { return term_; }  ///< The decomposed nonlinearity, shared.

  Scalar hamiltonian(const Vector& y) const;  ///< H(y) (a collective reduction).
  Scalar nonlinearValue(const Vector& y) const;  ///< N(y) = v^T G(y) (a collective reduction).
  /// out = grad H(y) = L y + f + J_G^T v.
  void gradient(const Vector& y, Vector& out) const;
  /// out = G(y) (unshifted row values G(y + reference())), a vector on the row map of G.
  void nonlinearRows(const Vector& y, Vector& out) const;
  /// out = grad N(y) = J_G(y)^T v.
  void nonlinearGradient(const Vector& y, Vector& out) const;
  /// The Jacobian J_G(y) (d x 2n) on nonlinearTerm().jacobianGraph().
  RCP<CrsMatrix> createJacobianG() const;
  void jacobianG(const Vector& y, CrsMatrix& out) const;  ///< out = J_G(y), on the matrix from createJacobianG().
  /// Hessian of N as a CrsMatrix on hessianGraph(false).
  RCP<CrsMatrix> createHessianN() const;
  void hessianN(const Vector& y, CrsMatrix& out) const;  ///< out = Hess N(y), on the matrix from createHessianN().
  /// target += scale * Hess H(y) = scale * (L + Hess N(y)), or scale * J Hess H(y) when leftJ;
  /// target fill-active on hessianGraph(leftJ). Off-rank rows are summed in at fillComplete().
  void addHessian(const Vector& y, Scalar scale, CrsMatrix& target, bool leftJ = false) const;
  /// Sparsity of Hess H = pattern(L) + pattern(Hess N) plus the diagonal, or of J Hess H plus the
  /// diagonal when leftJ (the Newton matrices I - dt J Hbar of the time integrators).
  RCP<const CrsGraph> hessianGraph(bool leftJ) const;
  /// target += scale * L (or scale * J L); target fill-active on a fill-complete graph.
  void addLinearPart(Scalar scale, CrsMatrix& target, bool leftJ = false) const;

 private:
  RCP<const PhaseSpace> space_;
  RCP<const CrsMatrix> L_;
  RCP<const Vector> f_;
  Scalar c_;
  RCP<const NonlinearTerm> term_;
  mutable NonlinearAssembly assembly_;
  mutable RCP<Vector> work_;
  mutable LocalScatter linScatter_[2];  ///< entries of L (rows mapped by J when leftJ)
  mutable std::vector<Scalar> linValues_, linBuf_;
  mutable RCP<const CrsGraph> hessGraph_[2];
};

}  // namespace gphr
