// Finite-difference checks of the assemblies every model path relies on, for both scenes:
// grad H against H, J_G against G, Hess N against grad N. Central differences with step h
// have truncation error O(h^2 |f'''|) and round-off O(eps_mach |f| / h); with h = 1e-5 relative
// to the point both stay below 1e-8 relative here, so the 1e-6 bound asserted has a margin of
// 100 without being loose enough to pass a wrong sign or a missing term (those give O(1)).
#include <gtest/gtest.h>

#include "TestUtils.hpp"
#include "gphr/models/Scene.hpp"

using namespace gphr;

namespace {

struct Case {
  std::string name;
  std::shared_ptr<Scene> scene;
  std::vector<double> mu;
  bool shift;
};

std::vector<Case> cases() {
  return {{"nls", std::make_shared<Nls1d>(64), {1.0932}, false},
          {"nls_shifted", std::make_shared<Nls1d>(64), {0.95}, true},
          {"nls_pulse_shifted", std::make_shared<Nls1d>(64, M_PI / 0.11, true), {1.05, 1.15, 0.35}, true},
          {"swe", std::make_shared<Swe2d>(8), {1.6435, 0.7762}, false},
          {"swe_shifted", std::make_shared<Swe2d>(8), {1.2, 1.1}, true}};
}

// A generic evaluation point: the initial state plus a smooth perturbation (so that every
// term, e.g. the SWE's Phi gradients, is non-zero).
RCP<Vector> point(const SceneInstance& s) {
  auto y = rcp(new Vector(*s.y0, Teuchos::Copy));
  Vector pert(y->getMap());
  test::fillByGid(pert, 0.3, 1);
  y->update(1.0, pert, 1.0);
  return y;
}

constexpr double kTol = 1e-6;  // see the header comment for the margin

class SceneFD : public ::testing::TestWithParam<int> {};

TEST_P(SceneFD, GradientMatchesFiniteDifferenceOfH) {
  const Case c = cases()[GetParam()];
  auto s = c.scene->instantiate(test::comm(), c.mu, c.shift);
  const auto& sys = *s.system;
  auto y = point(s);
  Vector g(sys.map()), d(sys.map()), yp(sys.map()), ym(sys.map());
  sys.gradient(*y, g);
  for (unsigned seed = 2; seed < 5; ++seed) {
    test::fillByGid(d, 1.0, seed);
    const double h = 1e-5 * y->norm2() / d.norm2();
    yp.update(1.0, *y, h, d, 0.0);
    ym.update(1.0, *y, -h, d, 0.0);
    const double fd = (sys.hamiltonian(yp) - sys.hamiltonian(ym)) / (2 * h), exact = g.dot(d);
    EXPECT_LE(std::abs(fd - exact), kTol * std::abs(exact)) << c.name << " seed " << seed;
  }
}

TEST_P(SceneFD, JacobianGMatchesFiniteDifferenceOfG) {
  const Case c = cases()[GetParam()];
  auto s = c.scene->instantiate(test::comm(), c.mu, c.shift);
  const auto& sys = *s.system;
  auto y = point(s);
  auto JG = sys.createJacobianG();
  sys.jacobianG(*y, *JG);
  const auto rowMap = sys.nonlinearTerm().rowMap();
  Vector d(sys.map()), yp(sys.map()), ym(sys.map()), gp(rowMap), gm(rowMap), Jd(rowMap);
  test::fillByGid(d, 1.0, 7);
  const double h = 1e-5 * y->norm2() / d.norm2();
  yp.update(1.0, *y, h, d, 0.0);
  ym.update(1.0, *y, -h, d, 0.0);
  sys.nonlinearRows(yp, gp);
  sys.nonlinearRows(ym, gm);
  gp.update(-1.0 / (2 * h), gm, 1.0 / (2 * h));
  JG->apply(d, Jd);
  gp.update(-1.0, Jd, 1.0);
  EXPECT_LE(gp.norm2(), kTol * Jd.norm2()) << c.name;
  // J_G^T v must be the gradient of N.
  Vector gradN(sys.map()), JtV(sys.map());
  sys.nonlinearGradient(*y, gradN);
  JG->apply(*sys.nonlinearTerm().weights(), JtV, Teuchos::TRANS);
  JtV.update(-1.0, gradN, 1.0);
  // Both sides sum the same few (<= stencil size) products per entry in a different order:
  // a few eps relative each; 1e-13 leaves a factor ~100 for the norm over 2n entries.
  EXPECT_LE(JtV.norm2(), 1e-13 * gradN.norm2()) << c.name;
}

TEST_P(SceneFD, HessianMatchesFiniteDifferenceOfGradient) {
  const Case c = cases()[GetParam()];
  auto s = c.scene->instantiate(test::comm(), c.mu, c.shift);
  const auto& sys = *s.system;
  auto y = point(s);
  auto Hn = sys.createHessianN();
  sys.hessianN(*y, *Hn);
  Vector d(sys.map()), yp(sys.map()), ym(sys.map()), gp(sys.map()), gm(sys.map()), Hd(sys.map());
  test::fillByGid(d, 1.0, 11);
  const double h = 1e-5 * y->norm2() / d.norm2();
  yp.update(1.0, *y, h, d, 0.0);
  ym.update(1.0, *y, -h, d, 0.0);
  sys.nonlinearGradient(yp, gp);
  sys.nonlinearGradient(ym, gm);
  gp.update(-1.0 / (2 * h), gm, 1.0 / (2 * h));
  Hn->apply(d, Hd);
  gp.update(-1.0, Hd, 1.0);
  EXPECT_LE(gp.norm2(), kTol * Hd.norm2()) << c.name;
}

INSTANTIATE_TEST_SUITE_P(Scenes, SceneFD, ::testing::Range(0, 4));

// eq:shiftH: H_s(y_s) = H(y_s + y0) exactly (to round-off of the sums, ~1e-14 relative).
TEST(Shift, ShiftedHamiltonianEqualsOriginalAtTranslatedState) {
  for (const auto& c : cases()) {
    auto [sys, y0] = c.scene->build(test::comm(), c.mu);
    auto shifted = sys->shifted(*y0);
    Vector ys(sys->map()), y(sys->map()), g(sys->map()), gs(sys->map());
    test::fillByGid(ys, 0.2, 3);
    y.update(1.0, ys, 1.0, *y0, 0.0);
    const double H = sys->hamiltonian(y), Hs = shifted->hamiltonian(ys);
    EXPECT_NEAR(Hs, H, 1e-12 * std::abs(H)) << c.name;
    EXPECT_NEAR(shifted->hamiltonian(Vector(sys->map())), sys->hamiltonian(*y0), 1e-12 * std::abs(H));
    sys->gradient(y, g);
    shifted->gradient(ys, gs);
    gs.update(-1.0, g, 1.0);
    EXPECT_LE(gs.norm2(), 1e-12 * g.norm2()) << c.name;
  }
}

// Scene::rebuild: a system at mu built on another system's layout (the model file's interpolation
// nodes) is the system build() makes at mu, to the last bit: the same values in the same
// structure, so L y, H, grad H and Hess N agree exactly, shifted or not; and the layout is shared,
// not rebuilt.
TEST(Scenes, RebuildOnALayoutEqualsBuild) {
  for (const auto& c : cases()) {
    const std::vector<double> other = c.mu.size() == 1   ? std::vector<double>{1.05}
                                      : c.mu.size() == 2 ? std::vector<double>{1.4, 0.9}
                                                         : std::vector<double>{0.92, 0.85, 0.6};
    const auto first = c.scene->instantiate(test::comm(), c.mu, c.shift);
    const auto fresh = c.scene->instantiate(test::comm(), other, c.shift);
    const auto reused = c.scene->instantiate(*first.system, other, c.shift);
    const auto& a = *fresh.system;
    const auto& b = *reused.system;
    EXPECT_EQ(b.nonlinearTerm().layout(), first.system->nonlinearTerm().layout()) << c.name;
    EXPECT_EQ(b.linearPart().getCrsGraph(), first.system->linearPart().getCrsGraph()) << c.name;
    EXPECT_EQ(b.constant(), a.constant()) << c.name;
    auto y = point(fresh);
    Vector La(a.map()), Lb(a.map()), ga(a.map()), gb(a.map()), d(a.map()), Ha(a.map()), Hb(a.map());
    a.linearPart().apply(*y, La);
    b.linearPart().apply(*y, Lb);
    a.gradient(*y, ga);
    b.gradient(*y, gb);
    EXPECT_EQ(a.hamiltonian(*y), b.hamiltonian(*y)) << c.name;
    test::fillByGid(d, 1.0, 7);
    auto HNa = a.createHessianN(), HNb = b.createHessianN();
    a.hessianN(*y, *HNa);
    b.hessianN(*y, *HNb);
    HNa->apply(d, Ha);
    HNb->apply(d, Hb);
    La.update(-1.0, Lb, 1.0), ga.update(-1.0, gb, 1.0), Ha.update(-1.0, Hb, 1.0);
    EXPECT_EQ(La.normInf(), 0.0) << c.name;
    EXPECT_EQ(ga.normInf(), 0.0) << c.name;
    EXPECT_EQ(Ha.normInf(), 0.0) << c.name;
    Vector y0(*fresh.physicalInitialState, Teuchos::Copy);
    y0.update(-1.0, *reused.physicalInitialState, 1.0);
    EXPECT_EQ(y0.normInf(), 0.0) << c.name;
  }
  // A layout of another scene or size is refused, naming both.
  const auto swe = Swe2d(8).instantiate(test::comm(), {1.4, 0.9}, false);
  EXPECT_THROW(Nls1d(64).rebuild(*swe.system, {1.0}), InputError);
  EXPECT_THROW(Swe2d(9).rebuild(*swe.system, {1.4, 0.9}), InputError);
  const auto nls = Nls1d(64).instantiate(test::comm(), {1.0}, false);
  EXPECT_THROW(Swe2d(8).rebuild(*nls.system, {1.4, 0.9}), InputError);
}

// J^T J = I exactly (J only permutes and flips signs); x^T J x = 0 up to the round-off of a
// dot product of 2n terms summed in another order (<= 2n eps ||x||^2).
TEST(PhaseSpace, CanonicalTensorIdentities) {
  PhaseSpace ps(37, test::comm());
  Vector x(ps.map()), Jx(ps.map()), back(ps.map());
  test::fillByGid(x, 1.0, 5);
  ps.applyJ(x, Jx);
  EXPECT_LE(std::abs(x.dot(Jx)), 2 * 74 * 2.3e-16 * x.dot(x));
  ps.applyJT(Jx, back);
  back.update(-1.0, x, 1.0);
  EXPECT_EQ(back.normInf(), 0.0);
  // J e_0 = -e_n (the p-row of q_0): column 0 of J is (0, -I)^T.
  Vector e(ps.map());  // zero-initialized; only the owner of gid 0 may write it
  if (ps.map()->isNodeGlobalElement(0)) e.replaceGlobalValue(0, 1.0);
  ps.applyJ(e, Jx);
  EXPECT_EQ(Jx.norm1(), 1.0);
  double val = 0.0;
  if (ps.map()->isNodeGlobalElement(37)) val = Jx.getData()[ps.map()->getLocalElement(37)];
  double gval = 0.0;
  Teuchos::reduceAll(*test::comm(), Teuchos::REDUCE_SUM, val, Teuchos::outArg(gval));
  EXPECT_EQ(gval, -1.0);
}

TEST(Scenes, RejectBadSizesAndParameters) {
  EXPECT_THROW(Nls1d(-4), InputError);
  EXPECT_THROW(Swe2d(2), InputError);
  Nls1d nls(16);
  EXPECT_THROW(nls.parameterBox().check({1.5}), InputError);
  EXPECT_NO_THROW(nls.parameterBox().check({1.0}));
  // Below the box too, and the message names the parameter, its value and the box.
  try {
    nls.parameterBox().check({0.5});
    FAIL() << "eps = 0.5 lies outside [0.9, 1.1] but no InputError was thrown";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("eps = 0.5"), std::string::npos) << msg;
    EXPECT_NE(msg.find("[0.9, 1.1]"), std::string::npos) << msg;
  }
}

// The grid a scene declares places each state entry where build() put it: the initial states
// are known functions of the coordinates (NLS |u0| = sqrt(2) / cosh x; SWE chi0 = 1 + exp(-beta
// |x|^2) / 2, Phi0 = 0), so a grid with a wrong origin, spacing or point order misses them by
// O(dx) while the right one reproduces them to round-off (1e-13).
TEST(Scenes, GridPlacesTheInitialStateAtItsCoordinates) {
  const auto comm = test::comm();
  const double beta = 1.6435;
  const std::vector<std::pair<std::shared_ptr<Scene>, std::vector<double>>> scenes{
      {std::make_shared<Nls1d>(40), {1.0}}, {std::make_shared<Swe2d>(7), {beta, 0.7762}}};
  for (const auto& [scene, mu] : scenes) {
    const auto grid = scene->grid();
    ASSERT_TRUE(grid.has_value()) << scene->name();
    const auto [system, y0] = scene->build(comm, mu);
    ASSERT_NO_THROW(grid->check(static_cast<GO>(y0->getGlobalLength()), scene->name()));
    const GO n = grid->numPoints();
    const auto& map = *y0->getMap();
    const auto y = y0->getLocalViewHost(Tpetra::Access::ReadOnly);
    for (LO l = 0; l < static_cast<LO>(map.getNodeNumElements()); ++l) {
      const GO gid = map.getGlobalElement(l);
      if (gid >= n) continue;  // the second component: checked through its partner (NLS) or zero (SWE)
      const LO partner = map.getLocalElement(gid + n);
      ASSERT_NE(partner, Teuchos::OrdinalTraits<LO>::invalid());  // q_i and p_i live on one rank
      double r2 = 0.0;
      GO rest = gid;
      for (size_t d = 0; d < grid->points.size(); ++d) {
        const double x = grid->origin[d] + grid->spacing[d] * static_cast<double>(rest % grid->points[d]);
        r2 += x * x;
        rest /= grid->points[d];
      }
      if (grid->complexField)
        EXPECT_NEAR(std::hypot(y(l, 0), y(partner, 0)), std::sqrt(2.0) / std::cosh(std::sqrt(r2)), 1e-13) << gid;
      else
        EXPECT_NEAR(y(l, 0), 1.0 + 0.5 * std::exp(-beta * r2), 1e-13) << gid;
    }
  }
  SceneGrid wrong = *Swe2d(7).grid();
  wrong.points = {7, 6};
  EXPECT_THROW(wrong.check(98, "swe2d"), InputError);
}

}  // namespace

// The Hamiltonians and initial states of doc/scenes.md evaluated from their formulas, by plain
// loops over the grid that share nothing with the scenes' L / f / G assembly, at a state whose
// entries are a formula of the global index (every rank computes the whole sum; the scene's H is
// the distributed one). Sums of ~n terms of size O(|H|): round-off ~n eps |H|, far below 1e-12.
namespace {
double wiggle(long gid) { return 0.3 * std::sin(1.7 * gid + 0.4) + 0.1 * std::cos(0.3 * gid); }

// y(gid) = wiggle(gid) on the system's map (gid < n: q or chi; gid >= n: p or Phi).
Vector formulaState(const HamiltonianSystem& sys) {
  Vector y(sys.map());
  auto v = y.getLocalViewHost(Tpetra::Access::OverwriteAll);
  for (size_t l = 0; l < v.extent(0); ++l) v(l, 0) = wiggle(sys.map()->getGlobalElement(static_cast<LO>(l)));
  return y;
}
}  // namespace

TEST(Scenes, NlsHamiltonianAndInitialStateAreDocScenesFormulas) {
  const int n = 48;
  const double eps = 1.0932, L = M_PI / 0.11, dx = 2 * L / n;
  auto [sys, y0] = Nls1d(n).build(test::comm(), {eps});
  // H = 1/2 q^T (-D_xx) q + 1/2 p^T (-D_xx) p - eps/4 sum (q^2 + p^2)^2, D_xx periodic central
  double H = 0.0;
  auto q = [&](long i) { return wiggle((i + n) % n); };
  auto p = [&](long i) { return wiggle(n + (i + n) % n); };
  for (long i = 0; i < n; ++i) {
    const double dq = (q(i + 1) - 2 * q(i) + q(i - 1)) / (dx * dx), dp = (p(i + 1) - 2 * p(i) + p(i - 1)) / (dx * dx);
    const double r2 = q(i) * q(i) + p(i) * p(i);
    H += -0.5 * q(i) * dq - 0.5 * p(i) * dp - eps / 4 * r2 * r2;
  }
  EXPECT_NEAR(sys->hamiltonian(formulaState(*sys)), H, 1e-12 * std::abs(H));
  // q + i p = sqrt(2) sech(x) exp(i x / 2), x_i = -L + i dx
  auto v = y0->getLocalViewHost(Tpetra::Access::ReadOnly);
  for (size_t l = 0; l < v.extent(0); ++l) {
    const long gid = y0->getMap()->getGlobalElement(static_cast<LO>(l)), i = gid % n;
    const double x = -L + i * dx, amp = std::sqrt(2.0) / std::cosh(x);
    EXPECT_NEAR(v(l, 0), gid < n ? amp * std::cos(x / 2) : amp * std::sin(x / 2), 1e-15) << "entry " << gid;
  }
}

// nls1d-pulse is nls1d with the pulse's amplitude a and velocity c as parameters: at the paper's
// a = 1, c = 1/2 the same system and y0 bit for bit; elsewhere y0 = a sqrt(2) sech(x) e^{i c x}
// (to 1e-15: the formula evaluated the same way), and H, L and G do not depend on a or c.
TEST(Scenes, NlsPulseIsNlsWithTheInitialPulseOfItsParameters) {
  const int n = 48;
  const double eps = 1.0932, L = M_PI / 0.11, dx = 2 * L / n;
  const Nls1d pulse(n, L, true), plain(n);
  EXPECT_EQ(pulse.name(), "nls1d-pulse");
  EXPECT_EQ(pulse.parameterBox().names, (std::vector<std::string>{"eps", "amplitude", "velocity"}));
  EXPECT_EQ(pulse.parameterBox().enters,
            (std::vector<unsigned>{EntersRowKernel, EntersInitialState, EntersInitialState}));
  auto [sysP, y0P] = pulse.build(test::comm(), {eps, 1.0, 0.5});
  auto [sys, y0] = plain.build(test::comm(), {eps});
  Vector d(*y0P, Teuchos::Copy);
  d.update(-1.0, *y0, 1.0);
  EXPECT_EQ(d.normInf(), 0.0);
  EXPECT_EQ(sysP->hamiltonian(formulaState(*sysP)), sys->hamiltonian(formulaState(*sys)));
  const double a = 1.15, c = 0.35;
  auto [sysAc, y0Ac] = pulse.build(test::comm(), {eps, a, c});
  EXPECT_EQ(sysAc->hamiltonian(formulaState(*sysAc)), sys->hamiltonian(formulaState(*sys)));
  auto v = y0Ac->getLocalViewHost(Tpetra::Access::ReadOnly);
  for (size_t l = 0; l < v.extent(0); ++l) {
    const long gid = y0Ac->getMap()->getGlobalElement(static_cast<LO>(l)), i = gid % n;
    const double x = -L + i * dx, amp = a * std::sqrt(2.0) / std::cosh(x);
    EXPECT_NEAR(v(l, 0), gid < n ? amp * std::cos(c * x) : amp * std::sin(c * x), 1e-15) << "entry " << gid;
  }
  EXPECT_THROW(pulse.build(test::comm(), {eps}), InputError);  // three parameters
}

TEST(Scenes, SweHamiltonianAndInitialStateAreDocScenesFormulas) {
  const int nx = 7, n = nx * nx;
  const double beta = 1.3, gamma = 0.9, dx = 4.0 / nx;
  auto [sys, y0] = Swe2d(nx).build(test::comm(), {beta, gamma});
  // H = gamma/2 sum chi^2 + gamma/2 sum chi [(D1 Phi)^2 + (D2 Phi)^2], i = a + nx b, periodic
  auto chi = [&](long a, long b) { return wiggle((a + nx) % nx + nx * ((b + nx) % nx)); };
  auto phi = [&](long a, long b) { return wiggle(n + (a + nx) % nx + nx * ((b + nx) % nx)); };
  double H = 0.0;
  for (long b = 0; b < nx; ++b)
    for (long a = 0; a < nx; ++a) {
      const double d1 = (phi(a + 1, b) - phi(a - 1, b)) / (2 * dx), d2 = (phi(a, b + 1) - phi(a, b - 1)) / (2 * dx);
      H += gamma / 2 * chi(a, b) * chi(a, b) + gamma / 2 * chi(a, b) * (d1 * d1 + d2 * d2);
    }
  EXPECT_NEAR(sys->hamiltonian(formulaState(*sys)), H, 1e-12 * std::abs(H));
  // chi = 1 + 1/2 exp(-beta |x|^2), Phi = 0, at (x1, x2) = (-2 + a dx, -2 + b dx)
  auto v = y0->getLocalViewHost(Tpetra::Access::ReadOnly);
  for (size_t l = 0; l < v.extent(0); ++l) {
    const long gid = y0->getMap()->getGlobalElement(static_cast<LO>(l)), i = gid % n;
    const double x1 = -2 + (i % nx) * dx, x2 = -2 + (i / nx) * dx;
    EXPECT_NEAR(v(l, 0), gid < n ? 1 + 0.5 * std::exp(-beta * (x1 * x1 + x2 * x2)) : 0.0, 1e-15) << "entry " << gid;
  }
}
