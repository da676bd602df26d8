// Empirical-quadrature term weights (gp-eqp, DESIGN.md "Term weights"), tested against mathematics:
//  - the NNLS fit: weights > 0 and finite, and the Karush-Kuhn-Tucker conditions of
//    min 1/2 ||C xi - b||^2, xi >= 0 at the end (gradient C^T (C xi - b) zero on the support,
//    >= 0 off it), on a synthetic system whose unconstrained solution has negative entries;
//  - every term allowed, zero tolerance: the fit is exact (xi = v) and the model is the reduced one;
//  - grad / Hess H_hr against finite differences, AVF conserves H_hr (the GP-DEIM model's checks);
//  - convexity inherited on the SWE at rest, where GP-DEIM's negative weights lose it;
//  - degenerate inputs give a result or a clear error, never a NaN.
#include <gtest/gtest.h>

#include <Teuchos_CommHelpers.hpp>

#include <functional>

#include "HyperTestUtils.hpp"
#include "gphr/hyper/EmpiricalQuadrature.hpp"

using namespace gphr;

namespace {

QuadratureTraining trainingOf(const test::HyperCase& hc, const QuadratureOptions& o = QuadratureOptions()) {
  return buildQuadratureTraining(hc.training, hc.snapshots, *hc.basis.A, o);
}

// A synthetic training system with d terms and R rows, column e a smooth function of (e, i) the
// same on any rank count: column 3 repeats column 1 and column 5 = column 1 + column 2 (exactly
// dependent columns), and b = C v for the given v.
QuadratureTraining synthetic(GO d, int R, const std::function<double(GO)>& v) {
  QuadratureTraining t;
  t.termMap = rcp(new Map(d, 0, test::comm()));
  t.numRows = R;
  t.columnFloor = 1e-6;
  auto column = [&](GO e, int i) -> double {
    if (e == 3) e = 1;
    if (e == 5) return std::cos(0.37 * i * 2 + 1.1) + std::cos(0.37 * i * 3 + 1.2);
    return std::cos(0.37 * i * (e + 1) + 1.0 + 0.1 * e);
  };
  const size_t nl = t.termMap->getNodeNumElements();
  std::vector<double> b(R, 0.0);
  double maxLocal = 0.0;
  for (size_t l = 0; l < nl; ++l) {
    const GO e = t.termMap->getGlobalElement(static_cast<LO>(l));
    double s = 0.0;
    for (int i = 0; i < R; ++i) {
      t.columns.push_back(column(e, i));
      s += column(e, i) * column(e, i);
      b[i] += v(e) * column(e, i);
    }
    t.norms.push_back(std::sqrt(s));
    t.v.push_back(v(e));
    maxLocal = std::max(maxLocal, t.norms.back());
  }
  t.target.resize(R);
  Teuchos::reduceAll(*test::comm(), Teuchos::REDUCE_SUM, R, b.data(), t.target.data());
  Teuchos::reduceAll(*test::comm(), Teuchos::REDUCE_MAX, maxLocal, Teuchos::outArg(t.maxNorm));
  t.snapshots = 1;
  return t;
}

// The largest KKT violations of a fit, relative to ||c_e|| ||b||: on the support |g_e|, off it
// max(0, -g_e), with g = C^T (C xi - b); and ||C xi|| / ||b||. Collective.
struct Kkt {
  double on, off, fitted;
};
Kkt kktViolations(const QuadratureTraining& t, const QuadratureFit& fit) {
  const int R = t.numRows;
  std::vector<double> r(t.target), ce(R);
  for (size_t j = 0; j < fit.terms.size(); ++j) {  // r = b - C xi, each active column gathered
    std::fill(ce.begin(), ce.end(), 0.0);
    const LO l = t.termMap->getLocalElement(fit.terms[j]);
    if (l >= 0) std::copy_n(t.columns.data() + static_cast<size_t>(l) * R, R, ce.data());
    std::vector<double> all(R);
    Teuchos::reduceAll(*test::comm(), Teuchos::REDUCE_SUM, R, ce.data(), all.data());
    for (int i = 0; i < R; ++i) r[i] -= fit.weights[j] * all[i];
  }
  double bn = 0.0;
  for (double x : t.target) bn += x * x;
  bn = std::sqrt(bn);
  double on = 0.0, off = 0.0;
  for (size_t l = 0; l < t.norms.size(); ++l) {
    if (!(t.norms[l] > t.columnFloor * t.maxNorm)) continue;  // not a candidate: not in the problem
    double g = 0.0;
    for (int i = 0; i < R; ++i) g -= t.columns[l * R + i] * r[i];
    const GO gid = t.termMap->getGlobalElement(static_cast<LO>(l));
    const bool active = std::find(fit.terms.begin(), fit.terms.end(), gid) != fit.terms.end();
    const double rel = g / (t.norms[l] * bn);
    if (active) on = std::max(on, std::abs(rel));
    else off = std::max(off, -rel);
  }
  double out[2] = {on, off}, all[2];
  Teuchos::reduceAll(*test::comm(), Teuchos::REDUCE_MAX, 2, out, all);
  double fitted = 0.0;
  for (int i = 0; i < R; ++i) fitted += (t.target[i] - r[i]) * (t.target[i] - r[i]);
  return {all[0], all[1], std::sqrt(fitted) / bn};
}

TEST(Eqp, NnlsWeightsArePositiveAndSatisfyKkt) {
  // v with negative entries: the unconstrained fit would need them, so constraints are active.
  const auto t = synthetic(30, 40, [](GO e) { return std::cos(0.9 * e); });
  const QuadratureFit fit = nnlsQuadrature(t, 30, 0.0);
  EXPECT_EQ(fit.stop, "optimal");
  ASSERT_FALSE(fit.terms.empty());
  double wmax = 0.0;
  for (double w : fit.weights) {
    EXPECT_GT(w, 0.0);
    EXPECT_TRUE(std::isfinite(w));
    wmax = std::max(wmax, w);
  }
  const Kkt k = kktViolations(t, fit);
  // On the support: C_P^T r = 0 up to the QR solve's backward error, eps cond(C_P) ~ 1e-13 here;
  // 1e-10 allows cond up to 1e5. Off it: candidates stop being chosen below a correlation of
  // sqrt(eps) = 1.5e-8 with the residual (selectTerm), so g_e >= -1.5e-8 ||c_e|| ||r||, and ||r|| <= ||b||.
  EXPECT_LE(k.on, 1e-10);
  EXPECT_LE(k.off, 1.5e-8);
  // Bounded: r is orthogonal to C_P xi (the support's least-squares solution), so
  // ||C_P xi||^2 + ||r||^2 = ||b||^2 and ||xi|| <= ||b|| / sigma_min(C_P); 1e-12 is the round-off of
  // the sums of squares.
  EXPECT_LE(k.fitted, 1.0 + 1e-12);
  EXPECT_NEAR(k.fitted * k.fitted + fit.residual * fit.residual, 1.0, 1e-12);
  std::printf("[eqp] synthetic NNLS: %zu terms, residual %.3e, KKT on %.2e off %.2e, largest weight %.3g\n",
              fit.terms.size(), fit.residual, k.on, k.off, wmax);
}

TEST(Eqp, DependentColumnsNeverEnterTogether) {
  // v = 1 on columns 1, 2 only: b = c_1 + c_2 = c_5 exactly; c_3 = c_1. One column fits b.
  const auto t = synthetic(8, 40, [](GO e) { return e == 1 || e == 2 ? 1.0 : 0.0; });
  const QuadratureFit fit = nnlsQuadrature(t, 8, 0.0);
  EXPECT_LE(fit.residual, 1e-12);
  const bool has1 = std::count(fit.terms.begin(), fit.terms.end(), 1), has3 = std::count(fit.terms.begin(), fit.terms.end(), 3);
  EXPECT_FALSE(has1 && has3) << "two identical columns in the active set";
  for (double w : fit.weights) EXPECT_TRUE(std::isfinite(w) && w > 0.0);
}

// A term that barely moves (column 1e-9 of the others) is not a candidate at the default floor,
// so it cannot take the unbounded weight that fitting its own direction would need.
TEST(Eqp, NegligibleColumnsAreNotCandidates) {
  auto t = synthetic(12, 40, [](GO e) { return e == 7 ? 1.0 : 0.0; });
  const LO l = t.termMap->getLocalElement(7);
  if (l >= 0) {
    for (int i = 0; i < t.numRows; ++i) t.columns[static_cast<size_t>(l) * t.numRows + i] *= 1e-9;
    t.norms[l] *= 1e-9;
  }
  t.target.assign(t.numRows, 0.0);
  const std::vector<double> c7 = [&] {  // b = c_7 (tiny), replicated
    std::vector<double> mine(t.numRows, 0.0), all(t.numRows);
    if (l >= 0) std::copy_n(t.columns.data() + static_cast<size_t>(l) * t.numRows, t.numRows, mine.data());
    Teuchos::reduceAll(*test::comm(), Teuchos::REDUCE_SUM, t.numRows, mine.data(), all.data());
    return all;
  }();
  t.target = c7;
  t.columnFloor = QuadratureOptions().columnFloor;
  const QuadratureFit fit = nnlsQuadrature(t, 12, 0.0);
  EXPECT_EQ(std::count(fit.terms.begin(), fit.terms.end(), 7), 0) << "the negligible column was selected";
  for (double w : fit.weights) EXPECT_TRUE(std::isfinite(w) && w >= 0.0);
  t.columnFloor = 0.0;  // admitted, it fits b exactly with weight 1 and nothing else is needed
  const QuadratureFit all = nnlsQuadrature(t, 12, 0.0);
  EXPECT_EQ(all.terms, std::vector<GO>{7});
}

// The greedy path through several budgets gives each budget's own fit: the same arithmetic in the
// same order, so the same numbers exactly.
TEST(Eqp, PathGivesEachBudgetsOwnFit) {
  auto hc = test::nlsCase(48, 4, test::comm());
  const auto t = trainingOf(hc);
  const std::vector<int> budgets = {20, 3, 8};
  const auto path = nnlsQuadraturePath(t, budgets, 0.0);
  ASSERT_EQ(path.size(), budgets.size());
  for (size_t i = 0; i < budgets.size(); ++i) {
    const QuadratureFit one = nnlsQuadrature(t, budgets[i], 0.0);
    EXPECT_EQ(path[i].terms, one.terms) << "budget " << budgets[i];
    EXPECT_EQ(path[i].weights, one.weights) << "budget " << budgets[i];
    EXPECT_EQ(path[i].stop, one.stop) << "budget " << budgets[i];
    EXPECT_EQ(path[i].terms.size(), static_cast<size_t>(budgets[i]));
  }
}

TEST(Eqp, EveryTermAndZeroToleranceReproducesTheReducedModel) {
  const GO n = 32;
  auto hc = test::nlsCase(n, 4, test::comm());
  QuadratureOptions every;
  every.columnFloor = 0.0;  // every term a candidate (the default floor drops 3 of 32 here)
  const auto t = trainingOf(hc, every);
  const QuadratureFit fit = nnlsQuadrature(t, static_cast<int>(n), 0.0);
  // C has full column rank d (the soliton moves every row), so the NNLS solution is xi = v = 1 with
  // residual at round-off: eps cond(C) ~ 1e-14 measured; 1e-10 leaves room for cond up to 1e6.
  EXPECT_LE(fit.residual, 1e-10);
  ASSERT_EQ(fit.terms.size(), static_cast<size_t>(n));
  for (double w : fit.weights) EXPECT_NEAR(w, 1.0, 1e-8);
  auto hr = buildQuadratureModel(*hc.test.system, *hc.basis.A, fit, reduceLinearPart(*hc.test.system, *hc.basis.A));
  GalerkinRom rom(hc.test.system, hc.basis.A);
  // Weights within 1e-8 of v perturb the vector field by 1e-8 relative; over 100 steps of a stable
  // scheme that stays below 1e-6 (the GP-DEIM m = d test, whose weights are exact, meets 1e-10).
  for (const char* scheme : {"imr", "avf"})
    EXPECT_LE(test::maxRelDiff(test::trajectory(*hr, scheme, 0.05, 100), test::trajectory(rom, scheme, 0.05, 100)), 1e-6)
        << scheme;
}

TEST(Eqp, DerivativesMatchFiniteDifferencesAndAvfConservesHhr) {
  auto hc = test::nlsCase(48, 4, test::comm());
  const auto t = trainingOf(hc);
  const auto linear = reduceLinearPart(*hc.test.system, *hc.basis.A);
  for (int m : {3, 8, 20}) {
    auto hr = buildQuadratureModel(*hc.test.system, *hc.basis.A, nnlsQuadrature(t, m, 0.0), linear);
    const auto d = test::checkDerivatives(*hr);  // tolerances: HyperTestUtils.hpp (kFdTol)
    EXPECT_LE(d.gradErr, test::kFdTol * d.gradNorm) << "grad H_hr vs FD, m = " << m;
    EXPECT_LE(d.hessErr, test::kFdTol * d.hessNorm) << "Hess H_hr vs FD of grad, m = " << m;
    EXPECT_LE(d.asym, 1e-7 * d.fdNorm) << "m = " << m;
    EXPECT_LE(test::avfDriftBeyondBound(*hr, 0.05, 1000), 0.0) << "m = " << m << ": AVF does not conserve H_hr";
  }
}

TEST(Eqp, DegenerateInputsGiveAResultOrAClearError) {
  auto hc = test::nlsCase(32, 3, test::comm());
  // Zero snapshots: every training run with no stored state.
  std::vector<RCP<const MultiVector>> none;
  for (const auto& s : hc.snapshots) none.push_back(rcp(new MultiVector(s->getMap(), 0)));
  try {
    buildQuadratureTraining(hc.training, none, *hc.basis.A, QuadratureOptions());
    FAIL() << "zero snapshots were accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no training states"), std::string::npos) << e.what();
  }
  // Rows beyond the memory guard: an error naming the keys that reduce them.
  QuadratureOptions small;
  small.maxNumbersPerRank = 100.0;
  try {
    trainingOf(hc, small);
    FAIL() << "a training system above the memory guard was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("eqp.sketchRows"), std::string::npos) << e.what();
  }
  const auto t = trainingOf(hc);
  const auto linear = reduceLinearPart(*hc.test.system, *hc.basis.A);
  // Budget 1 and a budget above d: a model with finite weights and a finite trajectory.
  for (int budget : {1, 32 + 10}) {
    const QuadratureFit fit = nnlsQuadrature(t, budget, 0.0);
    EXPECT_GE(fit.terms.size(), 1u);
    EXPECT_LE(fit.terms.size(), std::min<size_t>(budget, 32));
    for (double w : fit.weights) EXPECT_TRUE(std::isfinite(w) && w > 0.0) << "budget " << budget;
    auto hr = buildQuadratureModel(*hc.test.system, *hc.basis.A, fit, linear);
    for (const auto& z : test::trajectory(*hr, "avf", 0.05, 50))
      for (int i = 0; i < z.length(); ++i) ASSERT_TRUE(std::isfinite(z(i))) << "budget " << budget;
  }
  // Budget 0 and a negative tolerance: errors naming the value.
  EXPECT_THROW(nnlsQuadrature(t, 0, 0.0), InputError);
  EXPECT_THROW(nnlsQuadrature(t, 4, -1.0), InputError);
  // A zero target (v = 0 on a synthetic system): nothing to fit, said so.
  try {
    nnlsQuadrature(synthetic(10, 20, [](GO) { return 0.0; }), 4, 0.0);
    FAIL() << "a zero target was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("is zero"), std::string::npos) << e.what();
  }
}

TEST(Eqp, DuplicatedSnapshotsGiveTheSameFit) {
  auto hc = test::nlsCase(32, 3, test::comm());
  const auto once = nnlsQuadrature(trainingOf(hc), 8, 0.0);
  auto twice = hc;
  twice.training.insert(twice.training.end(), hc.training.begin(), hc.training.end());
  twice.snapshots.insert(twice.snapshots.end(), hc.snapshots.begin(), hc.snapshots.end());
  const auto two = nnlsQuadrature(trainingOf(twice), 8, 0.0);
  // Every row twice scales C^T C and C^T b by 2: the same correlations, the same solution; only
  // the order of the sums differs (1e-12 relative: round-off of R ~ 1e3-term sums).
  EXPECT_EQ(once.terms, two.terms);
  ASSERT_EQ(once.weights.size(), two.weights.size());
  for (size_t j = 0; j < once.weights.size(); ++j) EXPECT_NEAR(two.weights[j], once.weights[j], 1e-12 * once.weights[j]);
  EXPECT_NEAR(two.residual, once.residual, 1e-12);
}

// The refit's weights minimise the same residual GP-DEIM's weights have on the same terms, so its
// residual is never larger; exactRowsResidual (streamed, no C held) agrees with the fit's own
// residual on the same exact rows; the energy rows keep xi = v an exact fit.
TEST(Eqp, RefitNeverFitsWorseThanDeimWeightsAndResidualsAgree) {
  auto hc = test::nlsCase(32, 3, test::comm());
  QuadratureOptions o;
  o.energyWeight = 1.0;
  o.columnFloor = 0.0;  // every term a candidate, for the exact fit at the end
  const auto t = trainingOf(hc, o);
  const int m = 8;
  QuadratureFit deim;
  deim.terms = selectDeimIndices(*hc.deim.U, m);
  deim.weights = computeDeimWeights(*hc.deim.U, deim.terms, *hc.test.system->nonlinearTerm().weights()).weights;
  const QuadratureFit refit = refitQuadrature(t, deim.terms);
  const double deimRes = exactRowsResidual(hc.training, hc.snapshots, *hc.basis.A, o, deim);
  std::printf("[eqp] NLS 2k = 6, m = %d: residual DEIM weights %.3e, refit %.3e\n", m, deimRes, refit.residual);
  EXPECT_LE(refit.residual, deimRes * (1.0 + 1e-12));
  // Both are the same sum of squares in another order: 1e-10 relative.
  EXPECT_NEAR(exactRowsResidual(hc.training, hc.snapshots, *hc.basis.A, o, refit), refit.residual, 1e-10 * refit.residual);
  EXPECT_LE(nnlsQuadrature(t, 32, 0.0).residual, 1e-10);  // as in EveryTermAndZeroTolerance...
}

// A CountSketch of the rows: the fit on it is a fit (weights > 0, finite) and its exact-rows
// residual is reported beside the exact rows' fit (printed: the cost in accuracy).
TEST(Eqp, SketchedRowsGiveAFitAndItsExactResidual) {
  auto hc = test::nlsCase(48, 4, test::comm());
  const QuadratureFit exact = nnlsQuadrature(trainingOf(hc), 12, 0.0);
  for (int rows : {200, 800}) {
    QuadratureOptions o;
    o.sketchRows = rows;
    const auto t = trainingOf(hc, o);
    EXPECT_TRUE(t.sketched);
    EXPECT_EQ(t.numRows, rows);
    const QuadratureFit fit = nnlsQuadrature(t, 12, 0.0);
    for (double w : fit.weights) EXPECT_TRUE(std::isfinite(w) && w > 0.0);
    const double onExact = exactRowsResidual(hc.training, hc.snapshots, *hc.basis.A, o, fit);
    std::printf("[eqp] NLS 2k = 8, m = 12, %d exact rows: residual %.3e; sketch %d rows: %.3e (on the exact rows %.3e)\n",
                2 * 101 * 8, exact.residual, rows, fit.residual, onExact);
    // No bound against the exact rows' greedy fit: the selection on other rows picks other terms
    // (at 800 rows it found a fit 4x better on the exact rows than the exact rows' own). But on the
    // exact rows no weights on the chosen terms beat their least-squares refit there, which
    // exactRowsResidual must honour (the same sums in another order: 1e-10 relative).
    const QuadratureFit best = refitQuadrature(trainingOf(hc), fit.terms);
    EXPECT_GE(onExact, best.residual * (1.0 - 1e-10));
    // And the sketch is a sketch of these rows: a CountSketch of r rows embeds the 13-dimensional
    // span of the chosen columns and b with distortion ~ 13 / sqrt(r) (Clarkson & Woodruff 2013),
    // so the fit's residual on the sketched rows is its exact-rows residual within a factor
    // (1 + eps) / (1 - eps): measured 1.073 (200 rows) and 1.017 (800). A factor 2 either way fails
    // a sketch that lumps rows into few buckets (its fit is near exact on them) or ignores C.
    EXPECT_GT(fit.residual, 0.5 * onExact) << rows << " rows";
    EXPECT_LT(fit.residual, 2.0 * onExact) << rows << " rows";
    // The sketch keeps squared norms in expectation, E ||S c||^2 = ||c||^2 (by its signs: a
    // bucketing without them adds the products of the rows sharing a bucket). Summed over all
    // columns of C, and for b = C v; each ratio's spread is ~ sqrt(2 / rows) (0.1 at 200 rows:
    // measured 0.93 / 0.85 and 0.98 / 1.01), so [0.5, 2] is 5 standard deviations.
    const auto full = trainingOf(hc);
    double local[2] = {0.0, 0.0}, global[2], skb = 0.0, exb = 0.0;
    for (size_t l = 0; l < t.norms.size(); ++l)
      local[0] += t.norms[l] * t.norms[l], local[1] += full.norms[l] * full.norms[l];
    for (double x : t.target) skb += x * x;
    for (double x : full.target) exb += x * x;
    Teuchos::reduceAll(*test::comm(), Teuchos::REDUCE_SUM, 2, local, global);
    std::printf("[eqp] sketch %d rows: sum ||S c_l||^2 / sum ||c_l||^2 = %.4f, ||S b||^2 / ||b||^2 = %.4f\n", rows,
                global[0] / global[1], skb / exb);
    EXPECT_GT(global[0] / global[1], 0.5);
    EXPECT_LT(global[0] / global[1], 2.0);
    EXPECT_GT(skb / exb, 0.5);
    EXPECT_LT(skb / exb, 2.0);
    // Those ratios barely see dropped signs (the Jacobian rows' signs are mixed already: 1.13 /
    // 1.25 without them), but a column's sum does: a bucketing keeps sum_i (S c)_i = sum_rho c_rho
    // exactly, a signed sketch gives sum_rho s_rho c_rho, which differs unless the signed rows
    // cancel. So most columns' sums must differ from the exact rows' by more than round-off
    // (1e-9 of ||c||_1 against ~1e-16 x the row count for a bucketing).
    int kept = 0;
    for (size_t l = 0; l < t.norms.size(); ++l) {
      double sSketch = 0.0, sExact = 0.0, abs1 = 0.0;
      for (int i = 0; i < t.numRows; ++i) sSketch += t.columns[l * t.numRows + i];
      for (int i = 0; i < full.numRows; ++i)
        sExact += full.columns[l * full.numRows + i], abs1 += std::abs(full.columns[l * full.numRows + i]);
      if (std::abs(sSketch - sExact) <= 1e-9 * abs1) ++kept;
    }
    EXPECT_LT(kept, static_cast<int>(t.norms.size()) / 10 + 1) << kept << " of " << t.norms.size()
                                                               << " local columns kept their sums: no signs?";
  }
}

double largestEigenvalue(const DenseMatrix& H) {
  DenseMatrix minus(H);
  minus.scale(-1.0);
  return -smallestEigenvalue(minus);
}

// SWE at rest (Phi = 0, chi = chi0 > 0): Hess G_i = gamma chi_i (D^T D on Phi) is positive
// semi-definite, so with xi >= 0 Hess H_hr(0) = L_r + sum xi_e A^T Hess G_e A is too, while
// GP-DEIM's signed weights give it negative eigenvalues at some m (4 and 15 here: -4.4 measured,
// against |lambda_max| ~ 1e2). The floor -1e-10 |lambda_max| is the eigensolver's round-off
// (eps |lambda_max| ~ 1e-14) with margin; GP-DEIM's "clearly negative" is below -1e-3 |lambda_max|.
TEST(Eqp, ConvexityIsInheritedWhereGpDeimLosesIt) {
  Swe2d scene(20);
  auto hc = test::sceneCase(scene, {{1.1, 0.7}, {1.7, 0.7}, {1.1, 1.3}, {1.7, 1.3}}, {1.4, 1.0}, 10, 0.01, 100,
                            test::comm(), 100);
  const auto t = trainingOf(hc);
  const auto linear = reduceLinearPart(*hc.test.system, *hc.basis.A);
  const int r = static_cast<int>(hc.basis.A->getNumVectors());
  for (int m : {4, 15}) {
    auto gp = test::gpDeimModel(hc, m);
    auto eq = buildQuadratureModel(*hc.test.system, *hc.basis.A, nnlsQuadrature(t, m, 0.0), linear);
    DenseMatrix Hg(r, r), He(r, r);
    gp->addHessian(DenseVector(r), 1.0, Hg);
    eq->addHessian(DenseVector(r), 1.0, He);
    const double lg = smallestEigenvalue(Hg), le = smallestEigenvalue(He), Le = largestEigenvalue(He);
    std::printf("[eqp] SWE 20x20, 2k = %d, m = %d: lambda_min GP-DEIM %.3e (max %.3e), gp-eqp %.3e (max %.3e)\n", r, m,
                lg, largestEigenvalue(Hg), le, Le);
    EXPECT_LT(lg, -1e-3 * largestEigenvalue(Hg)) << "m = " << m << ": GP-DEIM was expected to lose convexity here";
    EXPECT_GE(le, -1e-10 * std::abs(Le)) << "m = " << m;
  }
}

}  // namespace
