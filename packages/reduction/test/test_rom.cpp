// The Galerkin reduced model (paper eq:red_model), tested against mathematics:
//  - a full basis (2k = 2n) reproduces the full trajectory to 1e-10 (both schemes step the same
//    system in rotated coordinates; the Newton tolerance 1e-12 bounds the difference);
//  - AVF conserves H_r(z) = H(A z) (same bound as the full model: |dH| <= |gbar| |R|);
//  - IMR conserves the NLS mass |A z|^2 = |z|^2 with a symplectic basis of either kind, which
//    commutes with J (unshifted model: the mass is then a quadratic invariant of the ROM);
//  - chord Newton (jacobianReuse) gives the same solution with fewer Newton-matrix assemblies;
//  - grad H_r and Hess H_r equal central differences of H_r and grad H_r (both scenes);
//  - L_r and f_r are the projections A^T L A and A^T f (formed a block of columns at a time).
#include <gtest/gtest.h>

#include "ReductionTestUtils.hpp"
#include "gphr/reduction/GalerkinRom.hpp"
#include "gphr/reduction/ReducedHamiltonian.hpp"
#include "gphr/reduction/SymplecticBasis.hpp"
#include "gphr/timeint/DenseModelIntegrator.hpp"

using namespace gphr;

namespace {

Teuchos::ParameterList integ(const std::string& scheme) {
  Teuchos::ParameterList pl("integrator");
  pl.set("scheme", scheme);
  pl.set("newtonTolerance", 1e-12);
  pl.sublist("linearSolver").set("tolerance", 1e-14);
  return pl;
}

// reduceLinearPart forms L A eight columns at a time (ReducedHamiltonian.cpp); here against the
// whole A^T (L A) with 21 columns (blocks of 8, 8 and 5), the NLS shifted so that f = L y0 is not
// zero. A's entries are O(1) over 2n = 120 rows and L's rows have 3 entries of O(1 / dx^2): each
// entry of L_r sums the same products in another order at most, a few hundred eps of the largest
// entry (1e-12 leaves room; a wrong block is O(1) off). L_r is symmetric to the last bit.
TEST(ReducedLinearPart, IsTheProjectionOfLAndF) {
  Nls1d scene(60);
  const auto s = scene.instantiate(test::comm(), {1.0}, true);
  const int r = 21;
  MultiVector A(s.system->map(), r), LA(s.system->map(), r);
  for (int j = 0; j < r; ++j) test::fillByGid(*A.getVectorNonConst(j), 1.0, static_cast<unsigned>(j + 3));
  s.system->linearPart().apply(A, LA);
  const std::vector<double> Lref = test::transposeTimes(A, LA);
  MultiVector f(s.system->map(), 1);
  Tpetra::deep_copy(*f.getVectorNonConst(0), s.system->linearForce());
  const std::vector<double> fref = test::transposeTimes(A, f);
  const ReducedLinearPart lin = reduceLinearPart(*s.system, A);
  ASSERT_EQ(lin.L.numRows(), r);
  double scaleL = 0.0, scaleF = 0.0, eL = 0.0, eF = 0.0;
  for (double x : Lref) scaleL = std::max(scaleL, std::abs(x));
  for (double x : fref) scaleF = std::max(scaleF, std::abs(x));
  ASSERT_GT(scaleF, 0.0);
  for (int i = 0; i < r; ++i) {
    eF = std::max(eF, std::abs(lin.f(i) - fref[i]));
    for (int j = 0; j < r; ++j) {
      eL = std::max(eL, std::abs(lin.L(i, j) - Lref[i * r + j]));
      EXPECT_EQ(lin.L(i, j), lin.L(j, i));
    }
  }
  EXPECT_LT(eL, 1e-12 * scaleL);
  EXPECT_LT(eF, 1e-12 * scaleF);
  EXPECT_EQ(lin.c, s.system->constant());
  // A basis of scattered columns (no single leading dimension) gives what its contiguous copy does.
  const std::vector<size_t> every2{0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20};
  const auto scattered = A.subView(Teuchos::ArrayView<const size_t>(every2.data(), every2.size()));
  ASSERT_FALSE(scattered->isConstantStride());
  const ReducedLinearPart a = reduceLinearPart(*s.system, *scattered);
  const ReducedLinearPart b = reduceLinearPart(*s.system, MultiVector(*scattered, Teuchos::Copy));
  for (int i = 0; i < 11; ++i) {
    EXPECT_EQ(a.f(i), b.f(i));
    for (int j = 0; j < 11; ++j) EXPECT_EQ(a.L(i, j), b.L(i, j));
  }
  EXPECT_NEAR(a.L(3, 5), lin.L(6, 10), 1e-12 * scaleL);  // columns 3, 5 of it are 6, 10 of A (other GEMM blocks)
}

TEST(GalerkinRom, FullBasisReproducesFullModel) {
  if (test::comm()->getSize() != 1) GTEST_SKIP() << "a full basis needs all dofs on one rank (TSQR)";
  const GO n = 10;
  Nls1d scene(n);
  auto s = scene.instantiate(test::comm(), {1.0}, false);
  // n generic complex snapshots: a full-rank data matrix, so the basis spans R^{2n}.
  auto snaps = rcp(new MultiVector(s.system->map(), n));
  for (GO j = 0; j < n; ++j) test::fillByGid(*snaps->getVectorNonConst(j), 1.0, static_cast<unsigned>(j + 1));
  PhaseSpace ps(n, test::comm());
  for (const char* method : {"psd", "cotangent"}) {
    BasisOptions opt;
    opt.method = method;
    opt.k = n;
    opt.maxRank = n;
    auto basis = computeSymplecticBasis({snaps}, ps, opt);
    for (const char* scheme : {"imr", "avf"}) {
      GalerkinRom rom(s.system, basis.A);
      DenseModelIntegrator romInt(rom, integ(scheme), 4);
      FullModelIntegrator fomInt(s.system, integ(scheme));
      Vector y(*s.y0, Teuchos::Copy), Az(s.system->map());
      DenseVector z = rom.project(y);
      std::vector<Vector> fom;
      fomInt.run(y, 0.02, 50, [&](long, double, const Vector& yj, const StepReport&) { fom.emplace_back(yj, Teuchos::Copy); });
      double worst = 0.0;
      romInt.run(z, 0.02, 50, [&](long j, double, const DenseVector& zj, const StepReport&) {
        rom.lift(zj, Az);
        Az.update(-1.0, fom[j], 1.0);
        worst = std::max(worst, Az.norm2() / fom[j].norm2());
      });
      EXPECT_LE(worst, 1e-10) << method << " " << scheme;
    }
  }
}

struct RomCase {
  RCP<HamiltonianSystem> system;
  ReducedBasis basis;
};

// A basis of size 2k trained on `steps` AVF steps at muTrain, and the system at muTest.
RomCase sceneRom(const Scene& scene, const std::vector<double>& muTrain, const std::vector<double>& muTest,
                 bool shift, const std::string& method, int k, double dt, long steps) {
  auto train = scene.instantiate(test::comm(), muTrain, shift);
  auto snaps = test::fomSnapshots(train, "avf", dt, steps);
  BasisOptions opt;
  opt.method = method;
  opt.k = k;
  auto test = scene.instantiate(test::comm(), muTest, shift);
  return {test.system, computeSymplecticBasis({snaps}, train.system->space(), opt)};
}

RomCase nlsRom(const std::string& method, bool shift) {
  return sceneRom(Nls1d(64), {1.0}, {1.05}, shift, method, 6, 0.02, 60);
}

TEST(GalerkinRom, AvfConservesReducedHamiltonian) {
  auto c = nlsRom("psd", true);
  GalerkinRom rom(c.system, c.basis.A);
  DenseModelIntegrator avf(rom, integ("avf"), 4);
  DenseVector z(rom.dim());  // shifted: z0 = A^T 0 = 0
  const double H0 = rom.hamiltonian(z);
  ASSERT_GT(std::abs(H0), 0.1);  // = H(y0) = 0.41 here: keeps the relative bound meaningful
  // AVF's discrete gradient: per step |dH| = |gbar^T R| <= |gbar| |R| for the Newton residual R
  // at acceptance, so the drift is at most the sum of those bounds, plus the round-off of
  // evaluating H (1e-13 (1 + |H0|): sums of ~1e2 terms of size |H0|). (A fixed 1e-9 |H0| was not
  // implied by the Newton tolerance: it held while Newton over-converged.)
  double beyond = 0.0, bound = 0.0;
  avf.run(z, 0.02, 300, [&](long j, double, const DenseVector& zj, const StepReport& rep) {
    if (j == 0) return;
    bound += avf.scheme().averageGradient().normFrobenius() * rep.residualNorm;
    beyond = std::max(beyond, std::abs(rom.hamiltonian(zj) - H0) - bound);
  });
  EXPECT_LE(beyond, 1e-13 * (1.0 + std::abs(H0)));
}

// The mass m(z) = z^T z is an invariant of the reduced NLS for these symplectic bases (z^T J
// grad H_r(z) = 0), and IMR conserves it exactly when its step equation is solved exactly: with
// the Newton residual R = z1 - z0 - dt J grad H_r((z0 + z1) / 2) at acceptance,
// m(z1) - m(z0) = (z1 - z0)^T (z1 + z0) = R^T (z1 + z0), so per step |dm| <= ||R|| (|z0| + |z1|)
// (+ round-off of m, 1e-14 m0). Over the run the drift is at most the sum of those bounds: the
// tolerance 1e-12 on ||R||, |z| = 2.1 (m0 = 4.5) and 300 steps give at most 1.3e-9 = 3e-10 m0.
// The former check, drift <= 1e-12 m0, was not implied by the
// tolerance: it held while Newton happened to over-converge (linear predictor).
TEST(GalerkinRom, ImrConservesMassWithSymplecticBasis) {
  for (const char* method : {"psd", "cotangent"}) {
    auto c = nlsRom(method, false);
    Nls1d scene(64);
    auto y0 = scene.build(test::comm(), {1.05}).second;
    GalerkinRom rom(c.system, c.basis.A);
    DenseModelIntegrator imr(rom, integ("imr"), 4);
    DenseVector z = rom.project(*y0), zPrev = z;
    const double m0 = z.dot(z);
    double worstRatio = 0.0, boundSum = 0.0, drift = 0.0;
    imr.run(z, 0.02, 300, [&](long j, double, const DenseVector& zj, const StepReport& rep) {
      if (j == 0) return;
      const double bound = rep.residualNorm * (zPrev.normFrobenius() + zj.normFrobenius()) + 1e-14 * m0;
      worstRatio = std::max(worstRatio, std::abs(zj.dot(zj) - zPrev.dot(zPrev)) / bound);
      boundSum += bound;
      drift = std::max(drift, std::abs(zj.dot(zj) - m0));
      zPrev = zj;
    });
    EXPECT_LE(worstRatio, 1.0) << method << ": a step changed the mass by more than ||R|| (|z0| + |z1|)";
    EXPECT_LE(drift, boundSum) << method;
    EXPECT_LE(drift, 1e-9 * m0) << method;  // the a priori sum of the per-step bounds, 3e-10 m0
  }
}

}  // namespace

namespace {
// The chord option changes only how Newton converges, not the solution: the trajectories differ
// by at most ~ steps x Newton tolerance x error growth = 100 x 1e-13 x O(10) = 1e-10.
// And it must take effect: chord Newton assembles (and LU-factors) one Newton matrix per step,
// full Newton one per iteration, i.e. >= 1 per step and more whenever a step needs 2 iterations.
TEST(GalerkinRom, JacobianReuseGivesTheSameSolution) {
  auto c = nlsRom("psd", true);
  GalerkinRom rom(c.system, c.basis.A);
  auto exact = integ("avf");
  exact.set("newtonTolerance", 1e-13);
  auto chord = exact;
  chord.set("jacobianReuse", true);
  DenseModelIntegrator a(rom, exact, 4), b(rom, chord, 4);
  DenseVector za(rom.dim()), zb(rom.dim());
  const RunStats sa = a.run(za, 0.02, 100);
  const RunStats sb = b.run(zb, 0.02, 100);
  za -= zb;
  EXPECT_LE(za.normFrobenius(), 1e-10);
  EXPECT_EQ(a.backend().newtonMatrixAssemblies(), sa.newtonIterations);  // full Newton: one per iteration
  EXPECT_LE(b.backend().newtonMatrixAssemblies(), 100);                  // chord: at most one per step
  EXPECT_LT(b.backend().newtonMatrixAssemblies(), a.backend().newtonMatrixAssemblies());
  EXPECT_GT(b.backend().newtonMatrixAssemblies(), 0);
  EXPECT_GE(sb.newtonIterations, sa.newtonIterations);  // linear instead of quadratic convergence
}

// GalerkinRom's derivatives against central differences of H_r and grad H_r, on both scenes,
// shifted and not (a wrong reduced Hessian only slows Newton down, so no trajectory test notices
// it). The point z is a reduced state of the training run plus a generic perturbation, so every
// term of H (NLS |u|^4, SWE chi |grad Phi|^2) contributes.
// Error of a central difference with step h along d, for H_r a polynomial of degree p <= 4 in z:
// truncation h^2/6 |D^3 f[d,d,d]| ~ (h |d| / |z|)^2 |Df[d]| = 1e-10 relative with
// h |d| = 1e-5 |z|; round-off eps_mach C |f| / (h |d|) ~ 2.2e-16 x 1e5 x C relative, where
// C <= ~10 is the cancellation among the terms of f (NLS: the Laplacian part against the
// quartic part), so <= ~2e-10. Measured: <= 5e-10 (gradient), <= 7e-11 (Hessian) on 1 and 2
// ranks. kFdTol = 1e-7 keeps a factor >= 200 above that, and is far below what a wrong term
// does: L_r missing, A^T Hess N A off by 1% or grad H_r off by 0.1% all fail (checked).
constexpr double kFdTol = 1e-7;

struct RomFdCase {
  std::string name;
  std::shared_ptr<Scene> scene;
  std::vector<double> mu;
  bool shift;
};

std::vector<RomFdCase> romFdCases() {  // both scenes at their test parameters, shifted and not
  std::vector<RomFdCase> out;
  for (bool shift : {false, true}) {
    const std::string tag = shift ? "_shifted" : "";
    out.push_back({"nls" + tag, std::make_shared<Nls1d>(64), {1.0932}, shift});
    out.push_back({"swe" + tag, std::make_shared<Swe2d>(8), {1.6435, 0.7762}, shift});
  }
  return out;
}

DenseVector genericDense(int dim, double scale, unsigned seed) {
  DenseVector v(dim);
  for (int i = 0; i < dim; ++i) v(i) = scale * std::sin(1.3 * i + 0.7 * seed + 0.1 * i * i / (1.0 + i));
  return v;
}

class RomDerivatives : public ::testing::TestWithParam<int> {
 protected:
  void SetUp() override {
    c_ = romFdCases()[GetParam()];
    auto s = c_.scene->instantiate(test::comm(), c_.mu, c_.shift);
    auto snaps = test::fomSnapshots(s, "avf", 0.01, 20);
    BasisOptions opt;
    opt.k = 4;
    basis_ = computeSymplecticBasis({snaps}, s.system->space(), opt).A;
    rom_ = std::make_unique<GalerkinRom>(s.system, basis_);
    z_ = rom_->project(*snaps->getVector(20));
    z_ += genericDense(rom_->dim(), 0.1 * z_.normFrobenius(), 1);
  }
  // d = the generic direction `seed`, zp/zm = z -+ h d with h |d| = 1e-5 |z|; returns h.
  double alongDirection(unsigned seed, DenseVector& d, DenseVector& zp, DenseVector& zm) const {
    d = genericDense(rom_->dim(), 1.0, seed);
    const double h = 1e-5 * z_.normFrobenius() / d.normFrobenius();
    zp = z_, zm = z_;
    DenseBackend::update(zp, h, d, 1.0);
    DenseBackend::update(zm, -h, d, 1.0);
    return h;
  }
  RomFdCase c_;
  RCP<MultiVector> basis_;
  std::unique_ptr<GalerkinRom> rom_;
  DenseVector z_;
};

TEST_P(RomDerivatives, GradientMatchesFiniteDifferenceOfHamiltonian) {
  const int dim = rom_->dim();
  DenseVector g(dim), d(dim), zp(dim), zm(dim);
  rom_->gradient(z_, g);
  for (unsigned seed = 2; seed < 5; ++seed) {
    const double h = alongDirection(seed, d, zp, zm);
    const double fd = (rom_->hamiltonian(zp) - rom_->hamiltonian(zm)) / (2 * h), exact = g.dot(d);
    EXPECT_LE(std::abs(fd - exact), kFdTol * std::abs(exact)) << c_.name << " seed " << seed;
  }
}

TEST_P(RomDerivatives, HessianMatchesFiniteDifferenceOfGradient) {
  const int dim = rom_->dim();
  DenseMatrix H(dim, dim);
  rom_->addHessian(z_, 1.0, H);
  DenseVector gp(dim), gm(dim), d(dim), zp(dim), zm(dim), Hd(dim);
  for (unsigned seed = 2; seed < 5; ++seed) {
    const double h = alongDirection(seed, d, zp, zm);
    rom_->gradient(zp, gp);
    rom_->gradient(zm, gm);
    Hd.multiply(Teuchos::NO_TRANS, Teuchos::NO_TRANS, 1.0, H, d, 0.0);
    DenseBackend::update(gp, -1.0 / (2 * h), gm, 1.0 / (2 * h));  // gp = FD of grad H_r along d
    gp -= Hd;
    EXPECT_LE(gp.normFrobenius(), kFdTol * Hd.normFrobenius()) << c_.name << " seed " << seed;
  }
}

// The averaged gradient sum_q w_q grad H_r(z_q), z_q = (1 - s_q) z0 + s_q z1, that the time
// scheme takes from the model at once (the stencil values combined from A_S z0 and A_S z1, one
// L_r product at the average point) equals the node-by-node sum. Both sum the same terms in
// another order: the difference is round-off, ~1e-15 relative times the cancellation between
// L_r z and the nonlinear part (<= ~10, see kFdTol), so 1e-12 relative. The call sequence also
// moves z1 with z0 fixed (A_S z0 reused) and then z0 (it must be recomputed), so a stale z0
// would fail (checked: an O(|z1 - z0|) error).
TEST_P(RomDerivatives, AveragedGradientEqualsNodeByNodeSum) {
  const int dim = rom_->dim();
  DenseVector z1 = z_, z0b = z_, gbar(dim), ref(dim), g(dim), zq(dim);
  z1 += genericDense(dim, 0.05 * z_.normFrobenius(), 7);
  z0b += genericDense(dim, 0.05 * z_.normFrobenius(), 8);
  for (int points : {1, 2, 3}) {
    const QuadratureRule rule = gaussLegendre(points);
    for (const auto& [z0, zz1] : {std::pair{z_, z1}, std::pair{z_, z0b}, std::pair{z0b, z1}}) {
      ASSERT_TRUE(rom_->averagedGradient(z0, zz1, rule, gbar));
      ref.putScalar(0.0);
      for (int q = 0; q < rule.size(); ++q) {
        DenseBackend::update(zq, 1.0 - rule.nodes[q], z0, rule.nodes[q], zz1, 0.0);
        rom_->gradient(zq, g);
        DenseBackend::update(ref, rule.weights[q], g, 1.0);
      }
      ref -= gbar;
      EXPECT_LE(ref.normFrobenius(), 1e-12 * gbar.normFrobenius()) << c_.name << ", " << points << " nodes";
    }
  }
}

// The averaged Hessian term of the Newton matrix, scale sum_q w_q s_q Hess H_r(z_q), that the
// time scheme takes from the model at once (L_r added once, the nodes' Hessian blocks summed
// before one A_S^T W product) equals the node-by-node sum of addHessian. Round-off again, so
// 1e-12 relative; the z0 moves are those of AveragedGradientEqualsNodeByNodeSum, and the
// averaged gradient is interleaved so that the kernel's cached A_S z0 is shared by both.
TEST_P(RomDerivatives, AveragedHessianEqualsNodeByNodeSum) {
  const int dim = rom_->dim();
  DenseVector z1 = z_, z0b = z_, gbar(dim), zq(dim);
  z1 += genericDense(dim, 0.05 * z_.normFrobenius(), 7);
  z0b += genericDense(dim, 0.05 * z_.normFrobenius(), 8);
  const double scale = -0.01;
  for (int points : {1, 2, 3}) {
    const QuadratureRule rule = gaussLegendre(points);
    for (const auto& [z0, zz1] : {std::pair{z_, z1}, std::pair{z_, z0b}, std::pair{z0b, z1}}) {
      DenseMatrix H(dim, dim), ref(dim, dim);
      ASSERT_TRUE(rom_->averagedGradient(z0, zz1, rule, gbar));
      ASSERT_TRUE(rom_->addAveragedHessian(z0, zz1, rule, scale, H));
      for (int q = 0; q < rule.size(); ++q) {
        DenseBackend::update(zq, 1.0 - rule.nodes[q], z0, rule.nodes[q], zz1, 0.0);
        rom_->addHessian(zq, scale * rule.weights[q] * rule.nodes[q], ref);
      }
      ref -= H;
      EXPECT_LE(ref.normFrobenius(), 1e-12 * H.normFrobenius()) << c_.name << ", " << points << " nodes";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, RomDerivatives, ::testing::Range(0, 4));

}  // namespace
