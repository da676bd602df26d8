#pragma once
// A small GP-DEIM set-up shared by the hyper-reduction tests: NLS training at two parameters,
// a PSD basis, the reduced-Jacobian DEIM basis, and GP-DEIM models of any size m.
#include "ReductionTestUtils.hpp"
#include "gphr/hyper/DeimBasis.hpp"
#include "gphr/hyper/GpDeimModel.hpp"
#include "gphr/reduction/Deim.hpp"
#include "gphr/reduction/GalerkinRom.hpp"
#include "gphr/reduction/SymplecticBasis.hpp"
#include "gphr/timeint/DenseModelIntegrator.hpp"

namespace gphr::test {

struct HyperCase {
  SceneInstance test;  // shifted system at the test parameter
  ReducedBasis basis;
  DeimBasis deim;
};

inline HyperCase sceneCase(const Scene& scene, const std::vector<std::vector<double>>& training,
                           const std::vector<double>& testMu, int k, double dt, long steps,
                           const RCP<const Comm>& c, int deimRank = 0) {
  std::vector<RCP<const HamiltonianSystem>> systems;
  std::vector<RCP<const MultiVector>> snaps;
  for (const auto& mu : training) {
    auto tr = scene.instantiate(c, mu, true);
    snaps.push_back(fomSnapshots(tr, "avf", dt, steps));
    systems.push_back(tr.system);
  }
  BasisOptions opt;
  opt.k = k;
  auto basis = computeSymplecticBasis(snaps, systems[0]->space(), opt);
  DeimBasisOptions dopt;
  dopt.maxRank = deimRank;
  auto deim = computeDeimBasis(systems, snaps, *basis.A, dopt);
  return {scene.instantiate(c, testMu, true), basis, deim};
}

// NLS on [-5, 5): the soliton covers the grid, so every row of G moves and the reduced-Jacobian
// snapshots have full numerical rank d (on the paper's [-28.6, 28.6) most rows sit at ~0).
inline HyperCase nlsCase(GO n, int k, const RCP<const Comm>& c) {
  Nls1d scene(n, 5.0);
  return sceneCase(scene, {{0.95}, {1.05}}, {1.0}, k, 0.05, 100, c, static_cast<int>(n));
}

inline RCP<GpDeimModel> gpDeimModel(const HyperCase& hc, int m, const std::string& method = "deim",
                                    DeimWeights* diag = nullptr) {
  return buildGpDeimModel(*hc.test.system, *hc.basis.A, *hc.deim.U, m, method, diag);
}

inline Teuchos::ParameterList denseIntegrator(const std::string& scheme, double tol = 1e-12) {
  Teuchos::ParameterList pl("integrator");
  pl.set("scheme", scheme);
  pl.set("newtonTolerance", tol);
  return pl;
}

// Trajectory z^0..z^steps of a dense model from z = 0 (the shifted initial state).
inline std::vector<DenseVector> trajectory(DenseHamiltonian& model, const std::string& scheme, double dt,
                                           long steps, int degree = 4) {
  DenseModelIntegrator integ(model, denseIntegrator(scheme), degree);
  DenseVector z(model.dim());
  std::vector<DenseVector> out;
  integ.run(z, dt, steps, [&](long, double, const DenseVector& zj, const StepReport&) { out.push_back(zj); });
  return out;
}

// max_j ||a_j - b_j|| / max_j ||b_j||
inline double maxRelDiff(const std::vector<DenseVector>& a, const std::vector<DenseVector>& b) {
  double num = 0.0, den = 0.0;
  for (size_t j = 0; j < std::min(a.size(), b.size()); ++j) {
    DenseVector d(a[j]);
    d -= b[j];
    num = std::max(num, d.normFrobenius());
    den = std::max(den, b[j].normFrobenius());
  }
  return num / den;
}

}  // namespace gphr::test
