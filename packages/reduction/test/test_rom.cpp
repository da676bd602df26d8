// The Galerkin reduced model (paper eq:red_model), tested against mathematics:
//  - a full basis (2k = 2n) reproduces the full trajectory to 1e-10 (both schemes step the same
//    system in rotated coordinates; the Newton tolerance 1e-12 bounds the difference);
//  - AVF conserves H_r(z) = H(A z) (same bound as the full model: |dH| <= |gbar| |R|);
//  - IMR conserves the NLS mass |A z|^2 = |z|^2 with a symplectic basis of either kind, which
//    commutes with J (unshifted model: the mass is then a quadratic invariant of the ROM).
#include <gtest/gtest.h>

#include "ReductionTestUtils.hpp"
#include "gphr/reduction/GalerkinRom.hpp"
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

RomCase nlsRom(const std::string& method, bool shift) {
  Nls1d scene(64);
  auto train = scene.instantiate(test::comm(), {1.0}, shift);
  auto snaps = test::fomSnapshots(train, "avf", 0.02, 60);
  PhaseSpace ps(64, test::comm());
  BasisOptions opt;
  opt.method = method;
  opt.k = 6;
  auto test = scene.instantiate(test::comm(), {1.05}, shift);
  return {test.system, computeSymplecticBasis({snaps}, ps, opt)};
}

TEST(GalerkinRom, AvfConservesReducedHamiltonian) {
  auto c = nlsRom("psd", true);
  GalerkinRom rom(c.system, c.basis.A);
  DenseModelIntegrator avf(rom, integ("avf"), 4);
  DenseVector z(rom.dim());  // shifted: z0 = A^T 0 = 0
  const double H0 = rom.hamiltonian(z);
  ASSERT_GT(std::abs(H0), 0.1);  // = H(y0) = 0.41 here: keeps the relative bound meaningful
  double drift = 0.0;
  avf.run(z, 0.02, 300, [&](long, double, const DenseVector& zj, const StepReport&) {
    drift = std::max(drift, std::abs(rom.hamiltonian(zj) - H0));
  });
  EXPECT_LE(drift, 1e-9 * std::abs(H0));
}

TEST(GalerkinRom, ImrConservesMassWithSymplecticBasis) {
  for (const char* method : {"psd", "cotangent"}) {
    auto c = nlsRom(method, false);
    Nls1d scene(64);
    auto y0 = scene.build(test::comm(), {1.05}).second;
    GalerkinRom rom(c.system, c.basis.A);
    DenseModelIntegrator imr(rom, integ("imr"), 4);
    DenseVector z = rom.project(*y0);
    const double m0 = z.dot(z);
    double worst = 0.0;
    imr.run(z, 0.02, 300, [&](long, double, const DenseVector& zj, const StepReport&) {
      worst = std::max(worst, std::abs(zj.dot(zj) - m0) / m0);
    });
    EXPECT_LE(worst, 1e-12) << method;  // Newton residual 1e-12 on |z| ~ 3, plus round-off
  }
}

}  // namespace

namespace {
// The chord option changes only how Newton converges, not the solution: the trajectories differ
// by at most ~ steps x Newton tolerance x error growth = 100 x 1e-13 x O(10) = 1e-10.
TEST(GalerkinRom, JacobianReuseGivesTheSameSolution) {
  auto c = nlsRom("psd", true);
  GalerkinRom rom(c.system, c.basis.A);
  auto exact = integ("avf");
  exact.set("newtonTolerance", 1e-13);
  auto chord = exact;
  chord.set("jacobianReuse", true);
  DenseModelIntegrator a(rom, exact, 4), b(rom, chord, 4);
  DenseVector za(rom.dim()), zb(rom.dim());
  a.run(za, 0.02, 100);
  const RunStats sb = b.run(zb, 0.02, 100);
  za -= zb;
  EXPECT_LE(za.normFrobenius(), 1e-10);
  EXPECT_GT(sb.newtonIterations, 0);
}
}  // namespace
