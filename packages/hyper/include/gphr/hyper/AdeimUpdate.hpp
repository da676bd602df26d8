#pragma once
/// @file
/// The rank-r update of the DEIM basis of GP-ADEIM (paper Sec.\ 4.1, alg:basis_adapt), on small
/// dense data: the rows P (interpolation, m; replicated) and S (sampling, m_s; replicated, or
/// distributed by rows over the ranks) of U_j and of the reduced-Jacobian window F_j (d x wbar,
/// wbar = 2k w). Nothing here is of size n or d.
///
///   C_j = (P^T U_j)^{-1} P^T F_j                                   DEIM coefficients (m x wbar)
///   S^T R_j = S^T U_j C_j - S^T F_j                                 residual at the sampling rows
///   (a, b) = argmin_{rank r} || S^T R_j + a b^T C_j ||_F            eq:min_prob
///   b_i: eigenvectors of  C (S^T R)^T (S^T R) C^T v = lambda C C^T v  for the r largest lambda  eq:gen_eval
///        taken in range(C_j) (b_i = Q_j z_i when C_j is rank-deficient, after theo:minprob_eig_equivalence)
///   a_i = -S^T R C^T b_i / ||C^T b_i||^2                            eq:ai_from_bi
///   S^T U_{j+1} = S^T U_j + a b^T,  the other rows unchanged       eq:Uupdate, eq:Scheck
#include <Teuchos_Comm.hpp>
#include <Teuchos_RCP.hpp>
#include <vector>

#include "gphr/core/DenseTypes.hpp"

namespace gphr {

/// Options of GP-ADEIM's rank-r update of the DEIM basis: the rank r, tau_r and the cut-off on C.
struct AdeimUpdateOptions {
  /// r: > 0 a fixed rank (capped by the numerical rank below); 0: the numerical rank of
  /// S^T R C^T with the relative tolerance rankTol (sigma_i > rankTol sigma_1: the scale of F
  /// does not matter, the paper's tau_r). Default 1e-12, the paper's choice for
  /// fig:error_vs_ctime_2k: C's singular values can spread over ten decades (NLS 2k = 160,
  /// m = 100), and S^T R C^T weighs each residual direction by them, so a cut at 1e-8 or 1e-10
  /// kept on average 28 or 54 of 100 directions and the directions left behind grew until the
  /// model failed (with coefficientTol 1e-12: E_L2 0.69 or 0.37 against 3.0e-3 at 1e-12;
  /// doc/design.md, 'GP-ADEIM', rank cut-offs).
  int rank = 0;
  double rankTol = 1e-12;  ///< tau_r, the relative tolerance of the numerical rank when rank = 0 (see rank).
  /// Directions of C with |R_ll| <= coefficientTol |R_11| in the column-pivoted QR of C^T are
  /// dropped (the rank-revealing route after theo:minprob_eig_equivalence; |R_ll| / |R_11| tracks
  /// sigma_l(C) / sigma_1(C)). The Gram matrix C C^T, whose condition number is cond(C)^2 (past
  /// 1e16 below sigma_l / sigma_1 = 1e-8), is never formed: the QR of C^T resolves directions
  /// down to its backward error, about wbar eps |R_11| (1e-13 at wbar = 400). The default 1e-10
  /// sits between two failures. A cut at 1e-8 left directions of C without update at NLS
  /// 2k = 160, m = 100, the same failure as rankTol above: C's numerical rank had a median of 74
  /// with both cut-offs at 1e-8, and with rankTol 1e-12 E_L2 was 3.7e-2 against 3.0e-3. A kept
  /// direction needs b ~ 1 / |R_ll|: at 1e-12 one update on the SWE (m = 50) made U too
  /// ill-conditioned for the Gram-based re-orthonormalization (refused by name).
  double coefficientTol = 1e-10;
};

/// The result of one rank-r update: C_j, the factors a and b of U_{j+1} = U_j + S a b^T, and the residuals.
struct AdeimUpdate {
  DenseMatrix C;                    ///< DEIM coefficients C_j (m x wbar)
  /// U_{j+1} = U_j + S a b^T. With r < r_C the columns are eq:gen_eval's eigenvectors b_i and
  /// eq:ai_from_bi's a_i; with r = r_C (every direction of C kept) only a b^T is defined by the
  /// update, and (a, b) = (-S^T R Q_1, T^+) is returned without the eigenvectors. Either way the
  /// columns of b lie in range(C_j) (b = T^+ W): of all minimisers of eq:min_prob, a b^T has the
  /// least Frobenius norm (a part of b in null(C_j^T) would leave the objective unchanged).
  DenseMatrix a;                    ///< m_s x r: the update of the rows S
  DenseMatrix b;                    ///< m x r
  std::vector<double> eigenvalues;  ///< all non-zero lambda of eq:gen_eval, descending (r-bar of them)
  int rank = 0;                     ///< r used (0: no update, the residual is zero)
  int coefficientRank = 0;          ///< numerical rank of C kept
  double residualBefore = 0.0;      ///< ||S^T R_j||_F
  double residualAfter = 0.0;       ///< ||S^T R_j + a b^T C_j||_F = sqrt(before^2 - sum_{i<=r} lambda_i)
};

/// C_j and its rank-revealing factor C^T Pi = Q R (LAPACK GEQP3), cut to the numerical rank r_C
/// (|R_ll| > coefficientTol |R_11|): C^T ~ Q_1 T with Q_1 (wbar x r_C) orthonormal and
/// T = [R11 R12] Pi^T. Q_1 Q_1^T = C^T (C C^T)^{-1} C is the projector C_bar of Lemma
/// theo:update_error and alg:indices_adapt, here without forming C C^T. Computed once per update,
/// shared by the resampling and the update.
struct CoefficientFactor {
  DenseMatrix C;     ///< m x wbar
  DenseMatrix Q;     ///< wbar x r_C, orthonormal columns spanning C's (numerical) row space
  DenseMatrix T;     ///< r_C x m: C^T ~ Q T
  DenseMatrix Tinv;  ///< m x r_C: T^+ = T^T (T T^T)^{-1}, the minimum-norm right inverse (T Tinv = I,
                     ///< columns in range(T^T) = range(C)); Pi R11^{-1} when r_C = m
  bool cut = false;  ///< r_C < min(m, wbar): directions of C dropped
  int rank() const { return Q.numCols(); }  ///< r_C, the numerical rank of C kept.
};
/// Factors C_j = (P^T U_j)^{-1} P^T F_j as CoefficientFactor describes.
CoefficientFactor factorCoefficients(const DenseMatrix& PtU, const DenseMatrix& PtF, double coefficientTol);
/// The same from C_j itself (deimCoefficients' result, taken over).
CoefficientFactor factorCoefficients(DenseMatrix C, double coefficientTol);

/// PtU: P^T U_j (m x m); PtF: P^T F_j (m x wbar); StU: S^T U_j (m_s x m); StF: S^T F_j (m_s x wbar).
/// InputError on mismatched sizes or a singular P^T U; never NaN: a zero residual or a zero C gives
/// rank 0 (no update).
AdeimUpdate computeAdeimUpdate(const DenseMatrix& PtU, const DenseMatrix& PtF, const DenseMatrix& StU,
                               const DenseMatrix& StF, const AdeimUpdateOptions& options);
/// The same from a factored C_j (options.coefficientTol is the factor's).
AdeimUpdate computeAdeimUpdate(const CoefficientFactor& factor, const DenseMatrix& StU, const DenseMatrix& StF,
                               const AdeimUpdateOptions& options);

/// This rank's share of the sampling rows S when the update runs on distributed rows: row i of the
/// local S^T U and S^T F is row positions[i] of S (of numRows), and every row of S is on exactly
/// one rank. comm null (or one rank): every row is here.
struct SampledRowShare {
  Teuchos::RCP<const Teuchos::Comm<int>> comm;  ///< Communicator over which S is distributed (null: all rows here).
  std::vector<int> positions;  ///< Position in S of each local row.
  int numRows = 0;  ///< m_s, the number of rows of S.
};

/// The same update with S^T U and S^T F distributed by rows (each rank passes its own rows): the
/// products of m_s rows (S^T R, M = S^T R Q_1 and the residual check) run on each rank's rows, and
/// one sum-reduction assembles the small M (m_s x r_C) everywhere, so the result (a replicated) is
/// the serial one to round-off on any rank count. Collective over share.comm.
AdeimUpdate computeAdeimUpdate(const CoefficientFactor& factor, const DenseMatrix& StUown, const DenseMatrix& StFown,
                               const AdeimUpdateOptions& options, const SampledRowShare& share);

/// StU += a b^T (the rows S of U_{j+1}).
void applyAdeimUpdate(const AdeimUpdate& update, DenseMatrix& StU);
/// The same on this rank's rows of S (share as in computeAdeimUpdate).
void applyAdeimUpdate(const AdeimUpdate& update, const SampledRowShare& share, DenseMatrix& StUown);

/// The DEIM coefficients C = (P^T U)^{-1} P^T F (LAPACK GETRF + GETRI, then one GEMM). InputError
/// naming the pivot when P^T U is singular.
DenseMatrix deimCoefficients(const DenseMatrix& PtU, const DenseMatrix& PtF);

}  // namespace gphr
