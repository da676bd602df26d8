#pragma once
/// @file
/// Term weights by empirical quadrature (DESIGN.md "Term weights: DEIM or non-negative
/// quadrature"; the ECSW / EQP idea of Farhat et al. and Yano & Patera). The hyper-reduced
/// Hamiltonian of eq:Hyperred_model is a weighted sum of sampled terms,
///   H_hr(z) = 1/2 z^T L_r z + z^T f_r + c + sum_{e in E} xi_e (G_e(y0 + A z) - G_e(y0)),
/// and GP-DEIM takes E = P, xi = (U^T P)^{-1} U^T v. Here E and xi solve a non-negative least
/// squares fit of the reduced model's nonlinear gradient over training states:
///   min_{xi >= 0, |E| <= m} || C xi - b ||,   C(:, e) = [A^T grad G_e(y0 + A z_s)]_s,   b = C v,
/// z_s = A^T y_s the projected, shifted training states (as for eq:snaps_JG; optionally one row per
/// state matching the energy G_e - G_e(y0) too). With xi >= 0, Hess H_hr = L_r + sum xi_e A^T Hess
/// G_e A is positive semi-definite wherever every term's Hessian is (the SWE at rest): H_hr keeps
/// the convexity that negative DEIM weights can destroy. The model online is GpDeimModel on the
/// sample mesh of (E, xi): the same code path.
#include <Teuchos_ParameterList.hpp>
#include <string>
#include <vector>

#include "gphr/core/HamiltonianSystem.hpp"
#include "gphr/core/SnapshotSet.hpp"
#include "gphr/core/SystemSet.hpp"
#include "gphr/hyper/GpDeimModel.hpp"

namespace gphr {

/// Options of the empirical-quadrature fit (config section eqp).
struct QuadratureOptions {
  int snapshotEvery = 1;      ///< use every N-th stored training state
  double energyWeight = 0.0;  ///< > 0: one more row per state, energyWeight (G_e(y_s) - G_e(y0)); 0: none
  int sketchRows = 0;         ///< > 0: CountSketch of the rows to this many; 0: the exact rows
  double columnFloor = 1e-3;  ///< columns with norm <= columnFloor * the largest are not candidates
  /// The exact rows are held as local terms x rows doubles per rank; above this the training stops
  /// with an error that names eqp.sketchRows and eqp.snapshotEvery (2.5e8: 2 GB).
  double maxNumbersPerRank = 2.5e8;
  unsigned long long seed = 20261124;  ///< the sketch's hash seed (sketchRows > 0)
};

/// The options of an `eqp` configuration section (validated: every key present).
QuadratureOptions quadratureOptionsFrom(const Teuchos::ParameterList& eqp);
/// The term-weight fits' cache key (core/CacheKey.hpp) for these training-system options and the
/// NNLS stopping tolerance; maxNumbersPerRank (a memory guard) is left out.
std::string quadratureCacheKey(const QuadratureOptions& options, double tolerance);
/// The keys of an `eqp` section with their defaults, ranges and documentation (quadratureOptionsFrom
/// reads them; `tolerance`, the fit's stopping residual, is the term-weight fits').
Teuchos::ParameterList quadratureValidParameters();

/// The training system of the fit: this rank's columns (its own rows of G, as their reduced-gradient
/// columns), the target b (replicated) and the column norms.
struct QuadratureTraining {
  RCP<const Map> termMap;        ///< the row map of G: column e lives on the rank owning row e
  int numRows = 0;               ///< rows of C (snapshots x (2k [+1]), or sketchRows)
  std::vector<double> columns;   ///< local columns, column l at columns[l * numRows]
  std::vector<double> target;    ///< b = C v, replicated
  std::vector<double> norms;     ///< ||C(:, l)|| of the local columns
  std::vector<double> v;         ///< the system's weights v of the local terms
  double maxNorm = 0.0;          ///< the largest column norm, over all ranks
  double columnFloor = 0.0;      ///< QuadratureOptions::columnFloor
  long snapshots = 0;            ///< training states used
  bool sketched = false;         ///< the rows are a CountSketch
};

/// Builds C and b from the training systems' stored states (shifted coordinates), streaming the
/// snapshots once. Collective. InputError: no training states, or the exact rows too large.
QuadratureTraining buildQuadratureTraining(const SystemSet& systems,
                                           const SnapshotSet& states, const MultiVector& A,
                                           const QuadratureOptions& options);

/// Terms E and weights xi of one fit, with its diagnostics.
struct QuadratureFit {
  std::vector<GO> terms;         ///< E, in the order selected
  std::vector<double> weights;   ///< xi_e >= 0 (nnls) or signed (refit), one per term
  double residual = 0.0;         ///< ||C xi - b|| / ||b|| on the fitted rows
  int iterations = 0;            ///< outer (selection) steps
  std::string stop;              ///< budget | tolerance | optimal (no term improves the fit) | iterations
  double seconds = 0.0;          ///< the solve (nnls: along the path up to this budget)
};

/// Greedy Lawson-Hanson NNLS: at most `budget` terms, stopping early once the relative residual is
/// <= tolerance or no candidate improves it. Deterministic on any rank count. Collective.
QuadratureFit nnlsQuadrature(const QuadratureTraining& training, int budget, double tolerance);
/// The same for several budgets in one pass: the greedy path passes through each budget in turn, so
/// fits[i] equals nnlsQuadrature(training, budgets[i], tolerance) at the cost of the largest alone.
std::vector<QuadratureFit> nnlsQuadraturePath(const QuadratureTraining& training, const std::vector<int>& budgets,
                                              double tolerance);

/// Signed least-squares weights for given terms (e.g. GP-DEIM's P) on the same rows. Collective.
QuadratureFit refitQuadrature(const QuadratureTraining& training, const std::vector<GO>& terms);

/// ||C xi - b|| / ||b|| of a fit on the exact training rows (streams the snapshots once more): what
/// sketching the rows costs. Collective.
double exactRowsResidual(const SystemSet& systems,
                         const SnapshotSet& states, const MultiVector& A,
                         const QuadratureOptions& options, const QuadratureFit& fit);

/// The hyper-reduced model of a fit: GpDeimModel on the sample mesh of (terms, weights). Collective.
RCP<GpDeimModel> buildQuadratureModel(const HamiltonianSystem& system, const MultiVector& A, const QuadratureFit& fit,
                                      const ReducedLinearPart& linear);

}  // namespace gphr
