#pragma once
// GP-ADEIM runs for the tests: the adaptive model integrated with its update hook after every
// step, recording the states and the model's Hamiltonian before each hook (H_hr^j of the local
// model that produced the step).
#include <functional>

#include "HyperTestUtils.hpp"
#include "gphr/hyper/GpAdeimModel.hpp"

namespace gphr::test {

struct AdaptiveRun {
  std::vector<DenseVector> z;
  std::vector<double> H;       // H_hr^j(z^tau), the local model of step tau
  std::vector<double> bound;   // per step: |gbar| |R| (the AVF conservation bound of that step)
};

inline AdeimOptions adeimOptions(int delta0, int delta, int gamma, int numSamples, const std::string& rule = "projected") {
  AdeimOptions o;
  o.initialWindow = delta0;
  o.updateEvery = delta;
  o.resampleEvery = gamma;
  o.numSamples = numSamples;
  o.sampling = rule;
  o.update.rankTol = 1e-10;
  return o;
}

// afterEach(step), if given, runs after the model's afterStep at every step.
inline AdaptiveRun adaptiveTrajectory(GpAdeimModel& model, const std::string& scheme, double dt, long steps,
                                      const std::function<void(long)>& afterEach = nullptr) {
  DenseModelIntegrator integ(model, denseIntegrator(scheme), 4);
  DenseVector z(model.dim());
  AdaptiveRun r;
  integ.run(z, dt, steps, [&](long j, double, const DenseVector& zj, const StepReport& rep) {
    r.z.push_back(zj);
    r.H.push_back(model.hamiltonian(zj));
    r.bound.push_back(j == 0 ? 0.0 : integ.scheme().averageGradient().normFrobenius() * rep.residualNorm);
    model.afterStep(j, zj);  // full Newton here (no lagged matrix to keep or reset)
    if (afterEach) afterEach(j);
  });
  return r;
}

}  // namespace gphr::test
