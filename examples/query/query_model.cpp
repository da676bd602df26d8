// Querying a reduced-model file from one's own code: load the file written by `gphr build`,
// take one of its hyper-reduced models at a few parameter values, run it with an observer that
// watches H_hr and the first probe (the lifted state at a stored entry), all without the full
// system: nothing of size n is built.
//   query_model MODEL.h5 [VALUE ...]      (values of the first parameter; default: the box's centre)
// Exit code 0 iff every run finishes and AVF or IMR keeps H_hr within 1e-8 of its start (the
// Newton tolerance bounds the drift per step; see doc/model-file.md).
#include <Tpetra_Core.hpp>

#include <cmath>
#include <cstdio>
#include <string>

#include "gphr/online/ReducedModel.hpp"

int main(int argc, char** argv) {
  Tpetra::ScopeGuard scope(&argc, &argv);
  if (argc < 2) {
    std::fprintf(stderr, "usage: query_model MODEL.h5 [VALUE ...]\n");
    return 2;
  }
  try {
    const gphr::ReducedModel file(argv[1]);
    const auto& data = file.data();
    const auto& stored = data.models.front();  // the file lists its models; take the first
    std::vector<double> mu;
    for (const auto& [lo, hi] : data.box) mu.push_back(0.5 * (lo + hi));
    std::vector<double> values;
    for (int i = 2; i < argc; ++i) values.push_back(std::stod(argv[i]));
    if (values.empty()) values.push_back(mu[0]);
    bool ok = true;
    for (double v : values) {
      mu[0] = v;
      auto online = file.instantiate(stored.method, stored.k, stored.m, mu);
      double H0 = 0.0, drift = 0.0, probe = NAN;
      const auto stats = online.simulate(data.T, data.dt, [&](const gphr::QueryStep& s) {
        if (s.step == 0) H0 = s.hamiltonian;
        drift = std::max(drift, std::abs(s.hamiltonian - H0));
        if (!s.probes.empty()) probe = s.probes.front();
      });
      std::printf("%s k=%d m=%d at %s = %g: %s, %ld steps in %.3f s (set-up %.1e s), |H_hr - H_hr(0)| <= %.2e, "
                  "first probe at T: %.6f\n", stored.method.c_str(), stored.k, stored.m, data.parameterNames[0].c_str(),
                  v, gphr::statusName(stats.status), stats.run.steps, stats.onlineSeconds, online.setupSeconds(), drift, probe);
      ok = ok && stats.ok() && drift <= 1e-8 * (1.0 + std::abs(H0));
    }
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "query_model: %s\n", e.what());
    return 2;
  }
}
