#pragma once
/// @file
/// The online error indicator of a query (doc/error-estimate.md): the full model's time-scheme
/// residual of the lifted reduced trajectory y^j = y0 + A z^j,
///   R_j = y^j - y^{j-1} - dt J sum_q w_q grad H(y^{j-1} + s_q (y^j - y^{j-1})),
/// evaluated on a fixed sample of s state entries Q only (the entries q_i and p_i of s/2 degrees of
/// freedom spread evenly over the n), as GNAT and libROM evaluate residuals on a sample mesh. J
/// maps the entries of one degree of freedom onto each other, so grad H is needed at Q itself: the
/// rows of G whose stencils hold an entry of Q (their own small sample mesh) and the rows Q of L A
/// and f, from the model file's parameter interpolant. Its cost per step is O(s k + terms s_G k),
/// whatever n.
///
/// From the residuals the indicator carries the scheme's linearised error equation
/// K e_j = (2I - K) e_{j-1} - R_j (doc/error-estimate.md) on those rows with K = I -- the
/// residuals summed, signs and all, no solve with K online, no transport of the error between
/// rows -- and forms eq:errNR's shape:
///   eta = sqrt( sum_j ||e_j,Q||^2 / sum_j ||y^j_Q||^2 ),   e_j,Q = -sum_{i <= j} R_i,Q,
/// numerator and denominator on the same rows. (Summing the residuals' norms instead, never
/// cancelling, missed the error's fall from k = 4 to 8 on the NLS: test_error_indicator.)
/// eta is an indicator, not an error: the model file
/// stores, per model, the calibration E_L2 ~ scale * eta^exponent fitted where the build knew the
/// true error (its training parameters), and a query reports that as its error estimate.
#include <vector>

#include "gphr/core/DenseTypes.hpp"
#include "gphr/core/Quadrature.hpp"
#include "gphr/core/NonlinearTerm.hpp"
#include "gphr/reduction/ReducedRowKernel.hpp"

namespace gphr {

/// The sample of the indicator for one reduced size k: parameter-free, stored in the model file.
struct IndicatorRows {
  /// Q: the sampled state entries, ascending: first the q entries of the sampled degrees of
  /// freedom, then their p entries in the same order (entries[i + s/2] is the partner of entries[i]).
  std::vector<GO> entries;
  std::vector<double> basisRows;  ///< A at Q (s x 2k, row-major)
  RowSample terms;                ///< the rows of G whose stencils hold an entry of Q, weights v (reference empty)
  bool empty() const { return entries.empty(); }  ///< No indicator (a file without one).
};

/// The degrees of freedom the indicator samples: `dofs` of 0 .. n - 1 spread evenly,
/// floor((i + 1/2) n / dofs) (all of them where dofs >= n). Empty for dofs = 0.
std::vector<GO> indicatorDofs(GO n, int dofs);
/// The indicator's rows for `system` (n from its phase space) and basis A: Q of indicatorDofs,
/// A's rows there, and the rows of G touching Q gathered with their stencils. Collective.
IndicatorRows indicatorRows(const HamiltonianSystem& system, const MultiVector& A, int dofs);

/// What the indicator needs at a parameter (from the file's interpolant or exactly): the rows Q of
/// L A (s x 2k, row-major) and of the shifted system's linear force f + L y0 (s).
struct IndicatorLinearRows {
  std::vector<double> LA;  ///< rows Q of L A, s x 2k row-major
  std::vector<double> f;   ///< rows Q of f + L y0 (the shifted system's linear force)
};
/// The rows Q of L A and f of a (shifted) system exactly (an O(n k) product). Collective.
IndicatorLinearRows indicatorLinearRows(const HamiltonianSystem& system, const MultiVector& A,
                                        const std::vector<GO>& entries);

/// E_L2 ~ scale * eta^exponent, fitted on the build's training parameters (doc/error-estimate.md).
struct IndicatorCalibration {
  double scale = 0.0;     ///< 0: not calibrated (no estimate is reported)
  double exponent = 1.0;  ///< fitted where eta spans a factor 2 over >= 3 points, else 1
  int points = 0;         ///< the training parameters the fit used
  /// Over those points, the largest factor between the estimate and the true E_L2 (>= 1).
  double worstFactor = 0.0;
  bool calibrated() const { return scale > 0.0; }  ///< Whether an estimate can be reported.
  double estimate(double eta) const;  ///< scale * eta^exponent (NaN if not calibrated or eta is not finite)
};

/// The least-squares fit of log E = log scale + exponent log eta over the pairs (eta, E) whose
/// both are finite and positive; the exponent is 1 (the scale their geometric mean ratio) where
/// fewer than 3 remain or eta spans less than a factor 2, and is kept within [0.5, 2] (the
/// indicator is a residual: its error is of the same order, up to the scheme's stability).
IndicatorCalibration fitIndicatorCalibration(const std::vector<double>& eta, const std::vector<double>& error);

/// The indicator along one reduced run (see the file's description): step() after each time step.
class ResidualIndicator {
 public:
  /// `kernel`: the row kernel at the query's parameter; `rows` the file's indicator rows;
  /// `reference` y0 at Q then at rows.terms' stencil entries; `linear` its rows at the parameter;
  /// `rule` the time scheme's quadrature rule.
  ResidualIndicator(RCP<const RowEvaluator> kernel, const IndicatorRows& rows, const std::vector<double>& reference,
                    IndicatorLinearRows linear, QuadratureRule rule);
  void start(const DenseVector& z0);  ///< At step 0 (z0 = 0 for a shifted run): resets the sums.
  /// After a step of size dt from z0 to z1: the residual on Q and the sums. z0 is the state of the
  /// previous call's (start's or step's) last state: its lift is reused.
  void step(const DenseVector& z0, const DenseVector& z1, double dt);
  double value() const;  ///< eta (NaN before start or where a residual was not finite)
  /// The residual R_Q of the last step (s numbers, Q's order), for tests.
  const std::vector<double>& lastResidual() const { return R_; }

 private:
  void liftU(const DenseVector& z, std::vector<double>& out) const;  ///< out = yU + AU z at every entry of U
  /// gN_ = grad N at Q, the row kernel run on the terms at the lift vU (U's values).
  void nonlinearGradientAtQ(const std::vector<double>& vU);
  IndicatorLinearRows linear_;
  QuadratureRule rule_;
  // U: the distinct entries of Q and of the terms' stencils (which overlap: a 5-point stencil puts
  // each entry under up to 5 rows), Q's first; the lift is formed once per distinct entry and step
  // (yU_ + AU_ z) and scattered into the batch by entryOf_.
  RCP<const RowEvaluator> kernel_;
  RowBatch batch_;
  std::vector<double> yU_, AU_, weight_;  ///< per entry of U: y0, A's row (row-major); per term row: v
  std::vector<double> vU0_, vU1_, vq_;    ///< the lifts at the step's two ends and at a quadrature node
  std::vector<int> qU_;                   ///< per entry of Q: its index in U
  std::vector<int> entryOf_, rowOf_, slot_;  ///< per stencil entry: its entry of U, its row, its index in Q (-1: none)
  std::vector<double> gN_, e_, gbar_, R_;
  DenseVector zbar_;
  int r_ = 0;
  double num_ = 0.0, den_ = 0.0;
  bool started_ = false;
};

}  // namespace gphr
