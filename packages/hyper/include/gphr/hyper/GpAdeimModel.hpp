#pragma once
/// @file
/// GP-ADEIM, the adaptive gradient-preserving hyper-reduced model (paper Sec.\ 4, alg:SP-ADEIM):
/// between updates the local model eq:lochr is exactly the GP-DEIM model of the current DEIM pair
/// (U_j, P_j) on its sample mesh; every `updateEvery` (delta) steps from `initialWindow` (delta0)
/// on, the rows S_j of the distributed DEIM basis U get the rank-r update of alg:basis_adapt from
/// the reduced-Jacobian window F_j of the last `window` (w) reduced states, P_{j+1} is re-chosen
/// from U_{j+1}, and the sample mesh moves with P (its new rows of A are gathered collectively).
/// Every `resampleEvery` (gamma) steps the sampling rows are re-chosen (alg:indices_adapt), which
/// evaluates F_j on all d rows, distributed over the ranks.
///
/// Online state: the sample mesh of P (as GpDeimModel), the one of S, the window (w x 2k), and
/// this rank's rows of U (d/p x m) with the kernel of its own rows for the resampling.
#include <Teuchos_ParameterList.hpp>
#include <deque>
#include <string>
#include <utility>

#include "gphr/hyper/AdeimUpdate.hpp"
#include "gphr/hyper/SampleMesh.hpp"

namespace gphr {

/// Hyper-parameters of GP-ADEIM (the `adeim` section): delta0, delta, w, gamma, r, tau_r, m_s, tau_s, rules.
struct AdeimOptions {
  int initialWindow = 5;   ///< delta0: first update after this many steps
  int updateEvery = 5;     ///< delta
  int window = 1;          ///< w: reduced states in F_j
  int resampleEvery = 5;   ///< gamma (a multiple of delta)
  AdeimUpdateOptions update;   ///< r (0: by tau_r), tau_r, the cut-off on C
  int numSamples = 0;      ///< m_s (>= m); 0: by sampleTol
  double sampleTol = 1e-3; ///< tau_s, relative to the largest row score (when numSamples = 0)
  int maxSamples = 0;      ///< cap with sampleTol; 0: 4 m
  std::string sampling = "projected";  ///< projected | residual | random
  std::string indices = "deim";        ///< P_{j+1} from U_{j+1}: deim | qdeim | partial (Peher15 Sec. 4.1)
  int pointUpdates = 1;                ///< partial: indices re-chosen per update (the most rotated columns)
  std::string initialBasis = "fom";    ///< (U_0, P_0): fom (delta0 FOM steps) | training
  bool monitorResidual = true;  ///< ||U_{j+1} C_j - F_j||_F on all d rows at every update (O(d))
  bool orthonormalize = true;  ///< U_{j+1} <- an orthonormal basis of its span (O(d m^2)): in column-pivoted QR order,
                               ///< or for indices = partial the nearest one (U G^{-1/2}), column by column
  unsigned long long seed = 20240601;  ///< Seed of the random sampling rule.
  /// An update runs only when the indicator ||S_j^T R_j||_F / ||S_j^T F_j||_F, the DEIM fit's
  /// relative residual at the current sampling rows, exceeds updateTol; otherwise U, P and S stay
  /// (a skipped update). 0: every delta steps, the paper's rule (the default). The first update
  /// always runs (no sampling rows yet).
  double updateTol = 0.0;
};

/// The `adeim` section: keys, defaults, ranges, documentation.
Teuchos::ParameterList adeimValidParameters();
/// The options of an `adeim` section, validated against adeimValidParameters() and checked where no
/// m is involved (w < delta0, gamma a multiple of delta, random sampling with m_s); maxSamples as
/// given (0: 4 m, resolved by adeimOptionsFor).
AdeimOptions adeimOptionsFrom(Teuchos::ParameterList pl);
/// `options` for DEIM size m: maxSamples 0 resolved to 4 m and the constraints that involve m
/// checked (m_s >= m, r <= m, ...). InputError naming the key.
AdeimOptions adeimOptionsFor(AdeimOptions options, int m);
/// adeimOptionsFor(adeimOptionsFrom(pl), m).
AdeimOptions adeimOptionsFrom(Teuchos::ParameterList pl, int m);
/// The `adeim` section that adeimOptionsFrom reads back as `options` (maxSamples as held): how a
/// model file stores gp-adeim's options.
Teuchos::ParameterList adeimParameters(const AdeimOptions& options);

/// One adaptation (one row of the report's adeim_updates.csv).
struct AdeimUpdateRecord {
  long step = 0;              ///< the time step after which it ran (ell_{j+1})
  int rank = 0;               ///< r used (0: the residual vanished, no update)
  int coefficientRank = 0;    ///< rank of C_j kept
  int numSamples = 0;         ///< m_s
  bool resampled = false;     ///< S re-chosen at this update
  double sampledBefore = 0.0; ///< ||S^T R_j||_F
  double sampledAfter = 0.0;  ///< ||S^T (U_{j+1} C_j - F_j)||_F
  double fullResidual = -1.0; ///< ||U_{j+1} C_j - F_j||_F over all d rows (fig:schro_samplingstrats); -1: not computed
  double windowNorm = -1.0;   ///< ||F_j||_F over all d rows, with fullResidual (the scale of its round-off); -1: not computed
  double condPtU = 0.0;       ///< cond_1(P_{j+1}^T U_{j+1}) of the new pair, LAPACK GECON estimate
  double hrBefore = 0.0;      ///< H_hr^j(z^{ell_{j+1}})   (the local model ending here)
  double hrAfter = 0.0;       ///< H_hr^{j+1}(z^{ell_{j+1}})
  double seconds = 0.0;       ///< wall time of this adaptation
  bool skipped = false;       ///< updateTol: the indicator stayed at or below it; nothing changed
  double indicator = -1.0;    ///< ||S_j^T R_j||_F / ||S_j^T F_j||_F before the update (updateTol > 0); -1: not computed
};

/// GP-ADEIM, the adaptive gradient-preserving hyper-reduced model (see the file's description).
class GpAdeimModel final : public ReducedHamiltonian {
 public:
  /// U0: the initial DEIM basis (d x >= m, on G's row map; copied). Collective.
  GpAdeimModel(RCP<const HamiltonianSystem> system, RCP<const MultiVector> A, const MultiVector& U0, int m,
               ReducedLinearPart linear, AdeimOptions options);

  /// Call after every time step with its number and state (step 0: the initial state). Adapts at
  /// the update steps of alg:SP-ADEIM and returns true when the model changed. Collective.
  bool afterStep(long step, const DenseVector& z);

  int deimSize() const { return m_; }  ///< m, the DEIM size.
  const std::vector<GO>& interpolationRows() const { return P_; }  ///< The interpolation rows P_j (global rows of G).
  const std::vector<GO>& samplingRows() const { return S_; }  ///< The sampling rows S_j (global rows of G).
  const std::vector<AdeimUpdateRecord>& updates() const { return records_; }  ///< One record per adaptation so far.
  const AdeimOptions& options() const { return opt_; }  ///< The options the model was built with.
  /// This rank's rows of the current DEIM basis U_j (d x m, distributed).
  const MultiVector& deimBasis() const { return *U_; }

 private:
  GpAdeimModel(RCP<const HamiltonianSystem> system, RCP<const MultiVector> A, RCP<MultiVector> U,
               ReducedLinearPart linear, AdeimOptions options);
  bool isUpdateStep(long step) const;
  void windowSnapshots(ReducedRowKernel& kernel, std::vector<double>& F);  ///< row-major rows x (2k w)
  double updateIndicator(const DenseMatrix& C, int wbar);  ///< ||S^T (U C - F)||_F / ||S^T F||_F (collective)
  void resample(const CoefficientFactor& cf, long updateNo);
  ReducedRowKernel& ownSampledKernel();  ///< this rank's rows of S, built on demand (no communication)
  AdeimUpdate updateSampledRows(const CoefficientFactor& cf, int wbar, std::vector<double>& F);
  /// ||U_{j+1} C_j - F_j||_F and ||F_j||_F over all d rows (the residual monitor).
  std::pair<double, double> fullResidual(const CoefficientFactor& cf);
  double moveInterpolationRows(const std::vector<double>& rotation);  ///< returns cond(P^T U)
  std::vector<double> columnRotations(const AdeimUpdate& up) const;  ///< ||(U_{j+1} - U_j) e_i|| / ||U_{j+1} e_i||
  void orthonormalizeBasis();

  RCP<const HamiltonianSystem> system_;
  RCP<const MultiVector> A_;
  RCP<const LocalRows> Arows_;  ///< A's local rows, row-major: the moving sample meshes gather from it
  RCP<MultiVector> U_;
  RCP<MultiVector> Unext_;  ///< the re-orthonormalization's product, swapped with U_ (allocated once)
  int m_;
  AdeimOptions opt_;
  std::vector<GO> P_, S_;
  DenseMatrix PtU_;                 ///< P_^T U_ (m x m) once gathered; empty before the first update
  RCP<ReducedRowKernel> owned_;     ///< this rank's rows of G (resampling, monitoring)
  RCP<ReducedRowKernel> ownSampled_;  ///< this rank's rows of S, copied from owned_; null after S changes
  std::vector<LO> ownSampledRows_;    ///< their local rows (U's local order)
  std::deque<DenseVector> window_;
  std::vector<double> ownedF_;      ///< F_j on this rank's rows (row-major), when computed
  bool ownedFValid_ = false;
  std::vector<AdeimUpdateRecord> records_;
};

/// (U_0, P_0)'s basis from the first delta0 full-model steps at the test parameter (alg:SP-ADEIM
/// line 2): the reduced-Jacobian snapshots J_G(y0 + A A^T y^l) A, l = 0..delta0, and their POD
/// (d x m) by the randomized range finder (m + 10 columns) with the QR projection, without power
/// passes: those square the spectrum, and so would the Gram projection, while these snapshots
/// carry only ~57 directions above 1e-7 sigma_1 at the paper's NLS (2k = 400): both cut below
/// m = 100. On that run 0.22 s against 0.87 s for the exact streaming POD (2 ranks).
/// `system`: the shifted system, `y0`: its initial state. Collective.
RCP<MultiVector> initialAdeimBasis(RCP<const HamiltonianSystem> system, const Vector& y0, const MultiVector& A,
                                   const Teuchos::ParameterList& integrator, double dt, int delta0, int m);

}  // namespace gphr
