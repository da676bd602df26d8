// Time integration of the full model, tested against mathematics:
//  - AVF conserves H: H(y1) - H(y0) = gbar^T R exactly (R the Newton residual), so per step
//    |dH| <= ||gbar|| ||R|| (+ round-off of H itself). With the Newton tolerance 1e-12 the
//    drift over 500 steps stays below the 1e-9 |H(y0)|.
//  - IMR conserves the quadratic invariant sum(q^2 + p^2) of the NLS.
//  - Both schemes have order 2.
//  - eps = 0 (linear NLS): both equal the dense Cayley recurrence of y' = J L y.
// These run with the default Newton driver (GPHR's loop), the AVF conservation also with NOX (whose
// last residual evaluation of a step must be that of the accepted y1, for averageGradient());
// test_nox compares the two drivers.
#include <gtest/gtest.h>

#include <Teuchos_LAPACK.hpp>
#include <Teuchos_SerialDenseMatrix.hpp>

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
  double Hprev = H0, worstRatio = 0.0, maxDrift = 0.0;
  integ.run(y, dt, 500, [&](long j, double, const Vector& yj, const StepReport& rep) {
    if (j == 0) return;
    const double H = s.system->hamiltonian(yj);
    const double bound = integ.scheme().averageGradient().norm2() * rep.residualNorm +
                         hamiltonianRound(H0, s.system->space().fullDim());
    worstRatio = std::max(worstRatio, std::abs(H - Hprev) / bound);
    maxDrift = std::max(maxDrift, std::abs(H - H0));
    Hprev = H;
  });
  EXPECT_LE(worstRatio, 1.0) << driver << ": a step changed H by more than ||gbar|| ||R|| + round-off";
  EXPECT_LE(maxDrift, 1e-9 * std::abs(H0)) << driver;
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
  double worst = 0.0;
  integ.run(y, 0.01, 500, [&](long, double, const Vector& yj, const StepReport&) {
    phys.update(1.0, yj, 1.0, *s.system->reference(), 0.0);
    worst = std::max(worst, std::abs(nlsMass(phys) - m0) / m0);
  });
  // Exact invariant of IMR: only the Newton residual (1e-12 absolute, mass ~ 10) and round-off
  // remain, hence 1e-12 relative.
  EXPECT_LE(worst, 1e-12);
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

}  // namespace
