// Time integration of the full model, tested against mathematics:
//  - AVF conserves H: H(y1) - H(y0) = gbar^T R exactly (R the Newton residual), so per step
//    |dH| <= ||gbar|| ||R|| (+ round-off of H itself), and the drift over 500 steps stays within
//    their sum, RunStats::driftBound (summary.json's H_drift_bound).
//  - IMR conserves the quadratic invariant sum(q^2 + p^2) of the NLS.
//  - Both schemes have order 2.
//  - eps = 0 (linear NLS): both equal the dense Cayley recurrence of y' = J L y.
//  - The Newton predictor (integrator.newtonPredictor = p): integrate() hands the stepper the
//    extrapolation through the last p + 1 states, exact for states polynomial of degree <= p in
//    the step index and not for degree p + 1; on the NLS, a higher order takes fewer Newton
//    iterations to the same tolerance and the same states (to the Newton tolerance).
// These run with the default Newton driver (GPHR's loop), the AVF conservation also with NOX (whose
// last residual evaluation of a step must be that of the accepted y1, for averageGradient());
// test_nox compares the two drivers.
#include <gtest/gtest.h>

#include <Teuchos_LAPACK.hpp>
#include <Teuchos_SerialDenseMatrix.hpp>
#include <cmath>
#include <vector>

#include "TestUtils.hpp"
#include "gphr/models/Scene.hpp"
#include "gphr/timeint/FullModelIntegrator.hpp"

using namespace gphr;

namespace {

Teuchos::ParameterList integratorParams(const std::string& scheme, double newtonTol) {
  Teuchos::ParameterList pl("integrator");
  pl.set("scheme", scheme);
  pl.set("newtonTolerance", newtonTol);
  pl.sublist("linearSolver").set("tolerance", 1e-14);
  return pl;
}

double hamiltonianRound(double H, GO n) { return 1e-15 * n * std::abs(H) + 1e-300; }

void checkAvfConservation(const Scene& scene, const std::vector<double>& mu, double dt, const char* driver) {
  auto s = scene.instantiate(test::comm(), mu, true);
  auto pl = integratorParams("avf", 1e-12);
  pl.set("newtonSolver", driver);
  FullModelIntegrator integ(s.system, pl);
  Vector y(*s.y0, Teuchos::Copy);
  const double H0 = s.system->hamiltonian(y);
  // Shifted system: H_s(0) = H(y0) is the constant c_s, away from 0 for both scenes (NLS 0.73,
  // SWE ~ 10^2), so the relative bound is meaningful.
  ASSERT_GT(std::abs(H0), 0.5);
  double Hprev = H0, worstRatio = 0.0, sum = 0.0, drift = 0.0;
  const RunStats stats = integ.run(y, dt, 500, [&](long j, double, const Vector& yj, const StepReport& rep) {
    if (j == 0) return;
    const double H = s.system->hamiltonian(yj), gbar = integ.scheme().averageGradient().norm2();
    const double bound = gbar * rep.residualNorm + hamiltonianRound(H0, s.system->space().fullDim());
    worstRatio = std::max(worstRatio, std::abs(H - Hprev) / bound);
    EXPECT_DOUBLE_EQ(rep.gradientNorm, gbar) << driver << ": the report's ||gbar|| is not the accepted step's";
    sum += gbar * rep.residualNorm;
    drift = std::max(drift, std::abs(H - H0));
    Hprev = H;
  });
  // The drift is then at most the sum of the steps' bounds; a fixed bound such as 1e-9 |H0| is
  // not implied by the Newton tolerance (it holds while Newton over-converges), so none is asserted.
  EXPECT_LE(worstRatio, 1.0) << driver << ": a step changed H by more than ||gbar|| ||R|| + round-off";
  // RunStats::driftBound (summary.json's H_drift_bound) is that sum, and bounds the whole drift
  // beyond the round-off of the 500 steps' H evaluations.
  EXPECT_NEAR(stats.driftBound, sum, 1e-12 * sum) << driver;
  EXPECT_LE(drift, stats.driftBound + 500 * hamiltonianRound(H0, s.system->space().fullDim())) << driver;
}

TEST(AVF, ConservesHamiltonianNls) {
  for (const char* d : {"gphr", "nox"}) checkAvfConservation(Nls1d(128), {1.0932}, 0.01, d);
}
TEST(AVF, ConservesHamiltonianSwe) {
  for (const char* d : {"gphr", "nox"}) checkAvfConservation(Swe2d(12), {1.6435, 0.7762}, 0.005, d);
}

TEST(IMR, ConservesNlsMass) {
  Nls1d scene(128);
  auto s = scene.instantiate(test::comm(), {1.0932}, true);
  FullModelIntegrator integ(s.system, integratorParams("imr", 1e-12));
  Vector y(*s.y0, Teuchos::Copy), phys(y.getMap());
  const double m0 = nlsMass(*s.physicalInitialState);
  // Exact invariant of IMR when its step equation is solved exactly: with the Newton residual
  // R = y1 - y0 - dt J grad H((y0 + y1) / 2) at acceptance and y^T J grad H(y) = 0 (the mass
  // ||y||^2 is an invariant of the NLS: its gradient 2 y is orthogonal to J grad H), m(y1) - m(y0) = (y1 - y0)^T (y1 + y0) = R^T (y1 + y0), so per
  // step |dm| <= ||R|| (|y0| + |y1|) (+ round-off of m: 1e-14 m0 over 256 entries); the drift is at
  // most the sum of those bounds. (A fixed 1e-12 m0 was not implied by the Newton tolerance:
  // 500 steps of ||R|| <= 1e-12 with |y| ~ 3 allow 3e-9.)
  double worstRatio = 0.0, boundSum = 0.0, drift = 0.0, mPrev = m0, worstResidual = 0.0;
  integ.run(y, 0.01, 500, [&](long j, double, const Vector& yj, const StepReport& rep) {
    phys.update(1.0, yj, 1.0, *s.system->reference(), 0.0);
    const double m = nlsMass(phys);
    if (j > 0) {
      worstResidual = std::max(worstResidual, rep.residualNorm);
      const double bound = rep.residualNorm * (std::sqrt(mPrev) + std::sqrt(m)) + 1e-14 * m0;
      worstRatio = std::max(worstRatio, std::abs(m - mPrev) / bound);
      boundSum += bound;
    }
    drift = std::max(drift, std::abs(m - m0));
    mPrev = m;
  });
  EXPECT_LE(worstRatio, 1.0) << "a step changed the mass by more than ||R|| (|y0| + |y1|)";
  EXPECT_LE(drift, boundSum);
  // The bounds scale with the reported ||R||: that it met the Newton tolerance (absolute ||R||_2 <=
  // 1e-12) makes them a priori ones, drift <= 500 (1e-12 (2 sqrt(m0) + ...) + 1e-14 m0).
  EXPECT_LE(worstResidual, 1e-12) << "a step was accepted above the Newton tolerance";
}

// Error at time T of the solution with step dt, measured against the solution with dt/2:
// e(dt) = ||y_dt - y_{dt/2}|| = C dt^2 (1 - 1/4) + O(dt^3), so e(dt)/e(dt/2) -> 4.
Vector solveTo(const Scene& scene, const std::vector<double>& mu, const std::string& scheme,
               double T, long steps) {
  auto s = scene.instantiate(test::comm(), mu, false);
  FullModelIntegrator integ(s.system, integratorParams(scheme, 1e-13));
  Vector y(*s.y0, Teuchos::Copy);
  integ.run(y, T / steps, steps);
  return y;
}

void checkOrder(const Scene& scene, const std::vector<double>& mu, const std::string& scheme, double T) {
  std::vector<Vector> ys;
  for (long steps : {10, 20, 40}) ys.push_back(solveTo(scene, mu, scheme, T, steps));
  ys[0].update(-1.0, ys[1], 1.0);
  ys[1].update(-1.0, ys[2], 1.0);
  const double ratio = ys[0].norm2() / ys[1].norm2();
  EXPECT_GE(ratio, 3.5) << scheme;
  EXPECT_LE(ratio, 4.5) << scheme;
}

TEST(Order, BothSchemesAreSecondOrderNls) {
  for (const char* s : {"imr", "avf"}) checkOrder(Nls1d(64), {1.0}, s, 1.0);
}
TEST(Order, BothSchemesAreSecondOrderSwe) {
  for (const char* s : {"imr", "avf"}) checkOrder(Swe2d(10), {1.4, 1.0}, s, 0.5);
}

// eps = 0: H = 1/2 y^T L y, both schemes reduce to (I - dt/2 JL) y1 = (I + dt/2 JL) y0.
TEST(Linear, EpsZeroEqualsDenseCayleyRecurrence) {
  if (test::comm()->getSize() != 1) GTEST_SKIP() << "dense reference is serial";
  const GO n = 16;
  const double dt = 0.05;
  Nls1d scene(n);
  auto [sys, y0] = scene.build(test::comm(), {0.0});
  // Dense J L.
  const int N = 2 * n;
  Teuchos::SerialDenseMatrix<int, double> A(N, N), B(N, N);
  Vector e(sys->map()), Le(sys->map()), JLe(sys->map());
  for (int c = 0; c < N; ++c) {
    e.putScalar(0.0);
    e.replaceGlobalValue(c, 1.0);
    sys->linearPart().apply(e, Le);
    sys->space().applyJ(Le, JLe);
    auto v = JLe.getData();
    for (int r = 0; r < N; ++r) {
      const GO g = sys->map()->getGlobalElement(r);
      A(g, c) = (g == c) - 0.5 * dt * v[r];
      B(g, c) = (g == c) + 0.5 * dt * v[r];
    }
  }
  std::vector<double> yd(N);
  {
    auto v = y0->getData();
    for (int r = 0; r < N; ++r) yd[sys->map()->getGlobalElement(r)] = v[r];
  }
  std::vector<int> piv(N);
  int info = 0;
  Teuchos::LAPACK<int, double> lapack;
  lapack.GETRF(N, N, A.values(), N, piv.data(), &info);
  ASSERT_EQ(info, 0);
  const int steps = 20;
  for (int j = 0; j < steps; ++j) {
    std::vector<double> rhs(N, 0.0);
    for (int r = 0; r < N; ++r)
      for (int c = 0; c < N; ++c) rhs[r] += B(r, c) * yd[c];
    lapack.GETRS('N', N, 1, A.values(), N, piv.data(), rhs.data(), N, &info);
    yd = rhs;
  }
  for (const char* scheme : {"imr", "avf"}) {
    FullModelIntegrator integ(sys, integratorParams(scheme, 1e-14));
    Vector y(*y0, Teuchos::Copy);
    integ.run(y, dt, steps);
    auto v = y.getData();
    double err = 0.0, nrm = 0.0;
    for (int r = 0; r < N; ++r) {
      const GO g = sys->map()->getGlobalElement(r);
      err = std::max(err, std::abs(v[r] - yd[g]));
      nrm = std::max(nrm, std::abs(yd[g]));
    }
    // Newton on a linear problem converges in one step up to the linear solve (1e-14 relative).
    EXPECT_LE(err, 1e-12 * nrm) << scheme;
  }
}

TEST(Newton, NonConvergenceNamesStepTimeAndResidual) {
  Nls1d scene(32);
  auto s = scene.instantiate(test::comm(), {1.0}, false);
  for (const char* driver : {"nox", "gphr"}) {
    auto pl = integratorParams("imr", 1e-12);
    pl.set("maxNewtonIterations", 1);
    pl.set("newtonSolver", driver);
    FullModelIntegrator integ(s.system, pl);
    Vector y(*s.y0, Teuchos::Copy);
    try {
      integ.run(y, 0.5, 3);
      FAIL() << driver << ": Newton with one iteration cannot reach 1e-12 at dt = 0.5";
    } catch (const SolverError& e) {
      std::cerr << e.what() << "\n";
      const std::string msg = e.what();
      EXPECT_NE(msg.find("step 1 (t = 0.5)"), std::string::npos) << msg;
      EXPECT_NE(msg.find("residual norm"), std::string::npos) << msg;
      EXPECT_NE(msg.find("after 1 iterations"), std::string::npos) << msg;
    }
  }
}

// A stepper that records the guess integrate() hands it and accepts the state poly(step) (a
// polynomial of the step index in every entry), with a backend on std::vector<double>.
struct VectorBackend {
  using Vector = std::vector<double>;
  Vector create() const { return Vector(3, 0.0); }
  static void update(Vector& y, double a, const Vector& x, double b) {
    for (size_t i = 0; i < y.size(); ++i) y[i] = a * x[i] + b * y[i];
  }
  static void update(Vector& y, double a, const Vector& x, double b, const Vector& z, double c) {
    for (size_t i = 0; i < y.size(); ++i) y[i] = a * x[i] + b * z[i] + c * y[i];
  }
  static void assign(Vector& y, const Vector& x) { y = x; }
};

struct PolynomialStepper {
  int degree;
  std::vector<std::vector<double>> guesses;  // guesses[j] = the guess for y^{j+1}
  std::vector<double> state(long step) const {  // entry e: sum_k (e + 1)^k (step / 4)^k, k <= degree
    std::vector<double> y(3, 0.0);
    for (int e = 0; e < 3; ++e)
      for (int k = 0; k <= degree; ++k) y[e] += std::pow(e + 1.0, k) * std::pow(step / 4.0, k);
    return y;
  }
  StepReport step(const std::vector<double>&, std::vector<double>& y1, double, long stepNo, double) {
    guesses.push_back(y1);
    y1 = state(stepNo);
    return StepReport{};
  }
};

// Largest |guess - y^{j+1}| over the steps from `from` on.
double guessError(int order, int degree, long steps, long from) {
  VectorBackend be;
  PolynomialStepper st{degree, {}};
  std::vector<double> y = st.state(0);
  integrate(st, be, y, 0.1, steps, nullptr, order);
  double err = 0.0;
  for (long j = from; j < steps; ++j) {
    const std::vector<double> exact = st.state(j + 1);
    for (int e = 0; e < 3; ++e) err = std::max(err, std::abs(st.guesses[j][e] - exact[e]));
  }
  return err;
}

TEST(Predictor, ExactForPolynomialsOfItsOrderOnly) {
  for (int order = 0; order <= kMaxPredictorOrder; ++order) {
    // From step `order` on, `order` past states are at hand. States reach ~ (3 * 12 / 4)^3 = 729:
    // round-off of the <= 15-term extrapolation stays below 1e-10.
    EXPECT_LE(guessError(order, order, 12, order), 1e-10) << "order " << order;
    // Degree order + 1: the guess misses by (order + 1)! * leading coefficient * (1/4)^(order + 1)
    // per entry (the finite-difference identity), at least (order + 1)! 4^-(order + 1) >= 0.09.
    EXPECT_GE(guessError(order, order + 1, 12, order), 0.09) << "order " << order;
  }
  // The first steps use the orders their history allows: step j (0-based) is exact for degree j.
  EXPECT_LE(guessError(3, 1, 2, 1), 1e-12);
  EXPECT_GE(guessError(3, 2, 2, 1), 0.09);
  VectorBackend be;
  PolynomialStepper st{1, {}};
  std::vector<double> y = st.state(0);
  EXPECT_THROW(integrate(st, be, y, 0.1, 1, nullptr, kMaxPredictorOrder + 1), InputError);
}

// On the NLS full model: each order takes fewer Newton iterations than the one below, and every
// order reaches the same states. Each step is solved to ||R|| <= 1e-12 whatever the guess, and
// AVF's step map is near-isometric (it conserves H), so after 40 steps the states differ by a
// few 40 x 1e-12 (bounded here by 1e-9 relative).
TEST(Predictor, HigherOrdersTakeFewerNewtonIterationsToTheSameStates) {
  Nls1d scene(64);
  auto s = scene.instantiate(test::comm(), {1.0}, false);
  std::vector<long> iterations;
  std::vector<Vector> finals;
  for (int order : {0, 1, 3}) {
    auto pl = integratorParams("avf", 1e-12);
    pl.set("newtonPredictor", order);
    pl.set("jacobianLag", true);  // the lagged matrix converges linearly (as in the benchmarks), so each order counts
    FullModelIntegrator integ(s.system, pl);
    Vector y(*s.y0, Teuchos::Copy);
    iterations.push_back(integ.run(y, 0.01, 40).newtonIterations);
    finals.push_back(y);
  }
  std::cerr << "Newton iterations over 40 steps, predictor 0 / 1 / 3: " << iterations[0] << " / " << iterations[1]
            << " / " << iterations[2] << "\n";
  EXPECT_LT(iterations[1], iterations[0]);
  EXPECT_LT(iterations[2], iterations[1]);
  for (size_t i = 1; i < finals.size(); ++i) {
    Vector d(finals[0], Teuchos::Copy);
    d.update(1.0, finals[i], -1.0);
    EXPECT_LE(d.norm2(), 1e-9 * finals[0].norm2()) << "predictor run " << i;
  }
}

}  // namespace
