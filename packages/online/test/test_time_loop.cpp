// The one observed time loop (TimeLoop.hpp) against mathematics, and the method registry.
// The loop runs the shifted harmonic oscillator H(z) = |z + c|^2 / 2, c = (1, 0), from z = 0: the
// implicit midpoint rule on a linear Hamiltonian system is its Cayley transform, a rotation of
// z + c by theta = 2 atan(dt / 2) per step, so z^j is known in closed form at every step and the
// loop's step count, times, order of calls and status are checked against it.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "gphr/core/Error.hpp"
#include "gphr/online/TimeLoop.hpp"

using namespace gphr;

namespace {

// H(z) = |z + c|^2 / 2 on R^2, c = (1, 0); gradient NaN from `nanFrom` calls on (to make it fail).
class ShiftedOscillator : public DenseHamiltonian {
 public:
  long gradientCalls = 0, nanFrom = -1;
  double energyOffset = 0.0;  ///< added to H alone (NaN: an H that overflowed while the dynamics did not)
  int dim() const override { return 2; }
  double hamiltonian(const DenseVector& z) override {
    return 0.5 * ((z(0) + 1.0) * (z(0) + 1.0) + z(1) * z(1)) + energyOffset;
  }
  void gradient(const DenseVector& z, DenseVector& g) override {
    const bool bad = nanFrom >= 0 && ++gradientCalls > nanFrom;
    g(0) = bad ? std::nan("") : z(0) + 1.0;
    g(1) = z(1);
  }
  void addHessian(const DenseVector&, double scale, DenseMatrix& H) override {
    H(0, 0) += scale;
    H(1, 1) += scale;
  }
};

SimulationSettings imr(double dt, long steps) {
  SimulationSettings s;
  s.dt = dt, s.steps = steps;
  s.integrator.set("scheme", "imr");
  s.integrator.set("newtonTolerance", 1e-13);
  return s;
}

TEST(TimeLoop, ImrIsTheCayleyRotationAtEveryObservedStep) {
  ShiftedOscillator model;
  const double dt = 0.05, theta = 2.0 * std::atan(dt / 2.0);
  const long steps = 200;
  std::vector<long> seen;
  double worst = 0.0;
  DenseVector z;
  const auto stats = simulate(model, imr(dt, steps), z, [&](long j, double t, const DenseVector& zj) {
    seen.push_back(j);
    EXPECT_DOUBLE_EQ(t, j * dt);
    // z^j + c = R(j theta) c, c = (1, 0): q = cos(j theta) - 1, p = -sin(j theta) (dq/dt = p, dp/dt = -(q + 1))
    worst = std::max({worst, std::abs(zj(0) - (std::cos(j * theta) - 1.0)), std::abs(zj(1) + std::sin(j * theta))});
  });
  EXPECT_TRUE(stats.ok()) << stats.reason;
  EXPECT_EQ(stats.lastStep, steps);
  EXPECT_EQ(stats.run.steps, steps);
  ASSERT_EQ(seen.size(), static_cast<size_t>(steps + 1));  // step 0 and every step, in order
  for (long j = 0; j <= steps; ++j) EXPECT_EQ(seen[j], j);
  // One Newton step solves each linear step to round-off (~1e-16); 200 rotations accumulate ~200 eps.
  EXPECT_LT(worst, 1e-12);
  EXPECT_NEAR(model.hamiltonian(z), 0.5, 1e-13);  // IMR conserves the quadratic H exactly
  EXPECT_GE(stats.onlineSeconds, 0.0);
  EXPECT_GE(stats.observeSeconds, 0.0);
}

TEST(TimeLoop, AdaptiveHookRunsAfterTheObserverAndItsFailureIsADivergence) {
  ShiftedOscillator model;
  std::vector<std::string> order;
  DenseVector z;
  const auto stats = simulate(
      model, imr(0.1, 10), z, [&](long j, double, const DenseVector&) { order.push_back("observe " + std::to_string(j)); },
      [&](long j, double, const DenseVector&) {
        order.push_back("adapt " + std::to_string(j));
        if (j == 4) throw SolverError("degenerate update");
      });
  EXPECT_EQ(stats.status, RunStatus::Diverged);
  EXPECT_FALSE(stats.ok());
  EXPECT_EQ(stats.reason, "degenerate update");
  EXPECT_EQ(stats.lastStep, 4);
  const std::vector<std::string> expected = {"observe 0", "adapt 0", "observe 1", "adapt 1", "observe 2",
                                             "adapt 2",   "observe 3", "adapt 3", "observe 4", "adapt 4"};
  EXPECT_EQ(order, expected);
}

TEST(TimeLoop, NonFiniteGradientEndsTheRunAsDivergedBeforeTheObserverSeesIt) {
  ShiftedOscillator model;
  model.nanFrom = 12;  // the gradient turns NaN after a few steps' worth of Newton evaluations
  DenseVector z;
  long observed = -1;
  const auto stats = simulate(model, imr(0.1, 50), z, [&](long j, double, const DenseVector&) { observed = j; });
  EXPECT_EQ(stats.status, RunStatus::Diverged);
  EXPECT_FALSE(stats.reason.empty());
  EXPECT_GT(stats.lastStep, 0);
  EXPECT_LT(stats.lastStep, 50);
  EXPECT_EQ(observed, stats.lastStep);  // no non-finite state reaches the observer
}

TEST(TimeLoop, WholeSteps) {
  EXPECT_EQ(wholeSteps(1.0, 0.1), 10);
  EXPECT_EQ(wholeSteps(50.0, 0.01), 5000);
  EXPECT_THROW(wholeSteps(1.0, 0.3), InputError);
  EXPECT_THROW(wholeSteps(1.0, 0.0), InputError);
  EXPECT_THROW(wholeSteps(0.05, 0.1), InputError);
  EXPECT_THROW(wholeSteps(std::nan(""), 0.1), InputError);
  try {
    wholeSteps(1.0, 0.3);
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not a whole number of steps"), std::string::npos) << e.what();
  }
}

}  // namespace

// A model whose state stays finite while its energy is not a number (a parameter box that made
// every H_hr NaN: status ok, drift 0) is not `ok` where H is observed: an observer that evaluates H
// through finiteHamiltonian (OnlineModel::simulate's, gphr run's) ends the run at step 0. Models
// without a Hamiltonian (the classic DEIM baselines: NaN by design) are run without it.
TEST(TimeLoop, ANonFiniteObservedHamiltonianIsADivergenceNotOk) {
  ShiftedOscillator model;
  model.energyOffset = std::nan("");
  DenseVector z;
  long observed = -1;
  const auto watched = simulate(model, imr(0.1, 10), z, [&](long j, double, const DenseVector& zj) {
    observed = j;
    finiteHamiltonian(model.hamiltonian(zj), j);
  });
  EXPECT_EQ(watched.status, RunStatus::Diverged);
  EXPECT_NE(watched.reason.find("non-finite Hamiltonian nan at step 0"), std::string::npos) << watched.reason;
  EXPECT_EQ(observed, 0);
  EXPECT_EQ(watched.lastStep, 0);
  EXPECT_TRUE(simulate(model, imr(0.1, 10), z).ok());  // not observed: the loop itself does not ask for H
  model.energyOffset = 1e300;  // large but finite: ok
  EXPECT_TRUE(simulate(model, imr(0.1, 10), z, [&](long j, double, const DenseVector& zj) {
                finiteHamiltonian(model.hamiltonian(zj), j);
              }).ok());
}
