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
  std::vector<RCP<const HamiltonianSystem>> training;  // shifted, one per training parameter
  std::vector<RCP<const MultiVector>> snapshots;       // their states (shifted coordinates)
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
  return {scene.instantiate(c, testMu, true), basis, deim, systems, snaps};
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

// Central differences with step h: truncation h^2/6 |f'''| plus round-off eps |f| / h. With
// h = 1e-5 and O(1) derivatives both are <= 1e-9 relative; 1e-6 leaves a wide margin and still
// catches any wrong term (a sign or factor error is O(1) relative).
constexpr double kFdStep = 1e-5, kFdTol = 1e-6;

inline DenseVector probePoint(int dim) {
  DenseVector z(dim);
  for (int i = 0; i < dim; ++i) z(i) = 0.3 * std::sin(1.7 * i + 0.4);
  return z;
}

inline DenseMatrix fdJacobianOfGradient(DenseHamiltonian& model, const DenseVector& z) {
  const int r = model.dim();
  DenseMatrix J(r, r);
  DenseVector zp(z), zm(z), gp(r), gm(r);
  for (int c = 0; c < r; ++c) {
    zp.assign(z), zm.assign(z);
    zp(c) += kFdStep, zm(c) -= kFdStep;
    model.gradient(zp, gp);
    model.gradient(zm, gm);
    for (int i = 0; i < r; ++i) J(i, c) = (gp(i) - gm(i)) / (2 * kFdStep);
  }
  return J;
}

// At probePoint: grad H against central differences of H, Hess H against central differences of
// grad H, and the asymmetry of the latter (a gradient field has a symmetric Jacobian), each with
// the norm it is measured against.
struct DerivativeCheck {
  double gradErr, gradNorm, hessErr, hessNorm, asym, fdNorm;
};
inline DerivativeCheck checkDerivatives(DenseHamiltonian& model) {
  const int r = model.dim();
  const DenseVector z = probePoint(r);
  DenseVector g(r), zp(z), zm(z);
  model.gradient(z, g);
  double err = 0.0;
  for (int c = 0; c < r; ++c) {
    zp.assign(z), zm.assign(z);
    zp(c) += kFdStep, zm(c) -= kFdStep;
    const double fd = (model.hamiltonian(zp) - model.hamiltonian(zm)) / (2 * kFdStep);
    err = std::max(err, std::abs(fd - g(c)));
  }
  DenseMatrix H(r, r);
  model.addHessian(z, 1.0, H);
  const DenseMatrix Jfd = fdJacobianOfGradient(model, z);
  DenseMatrix diff(Jfd), asym(Jfd, Teuchos::TRANS);
  diff -= H;
  asym -= Jfd;
  return {err, g.normInf(), diff.normInf(), H.normInf(), asym.normInf(), Jfd.normInf()};
}

// AVF from z = 0: the largest |H(z_j) - H(z_0)| beyond the scheme's bound, which per step is
// |dH| = |gbar^T R| <= |gbar| |R| (AveragedGradientScheme), summed over the steps, plus the
// round-off of evaluating H twice (1e-13 (1 + |H0|): sums of ~1e2 terms of size |H0|). <= 0: conserved.
inline double avfDriftBeyondBound(DenseHamiltonian& model, double dt, long steps) {
  DenseModelIntegrator avf(model, denseIntegrator("avf"), 4);
  DenseVector z(model.dim());
  const double H0 = model.hamiltonian(z);
  double bound = 0.0, worst = 0.0;
  avf.run(z, dt, steps, [&](long j, double, const DenseVector& zj, const StepReport& rep) {
    if (j == 0) return;
    bound += avf.scheme().averageGradient().normFrobenius() * rep.residualNorm;
    worst = std::max(worst, std::abs(model.hamiltonian(zj) - H0) - bound - 1e-13 * (1.0 + std::abs(H0)));
  });
  return worst;
}

}  // namespace gphr::test
