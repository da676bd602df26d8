// GP-DEIM (paper Sec. 3), tested against mathematics:
//  - m = d: the DEIM projection is the identity (U square and invertible gives w = v), so the
//    hyper-reduced trajectory is the reduced one; both step the same equations with the same
//    Newton tolerance 1e-12, summed in another order: 1e-10 relative;
//  - grad H_hr against central differences of H_hr, Hess H_hr against central differences of
//    grad H_hr (so Newton's matrix is right), and the finite-difference Jacobian of grad H_hr is
//    symmetric: a gradient field;
//  - AVF conserves H_hr: |H(z1) - H(z0)| = |gbar^T R| <= |gbar| |R| per step;
//  - the online object does not grow with n (SWE 32^2 .. 128^2 at fixed k, m);
//  - extremes run or fail with a message naming the cause.
#include <gtest/gtest.h>

#include <Teuchos_LAPACK.hpp>

#include "HyperTestUtils.hpp"
#include "gphr/hyper/GradientDeimModel.hpp"
#include "gphr/reduction/ReducedRowKernel.hpp"

using namespace gphr;

namespace {

TEST(GpDeim, FullDeimSizeReproducesReducedModel) {
  const GO n = 32;
  auto hc = test::nlsCase(n, 4, test::comm());
  ASSERT_EQ(hc.deim.U->getNumVectors(), static_cast<size_t>(n)) << "the snapshots must span R^d for this test";
  auto hr = test::gpDeimModel(hc, static_cast<int>(n));
  GalerkinRom rom(hc.test.system, hc.basis.A);
  for (const char* scheme : {"imr", "avf"}) {
    const auto zr = test::trajectory(rom, scheme, 0.05, 100);
    const auto zh = test::trajectory(*hr, scheme, 0.05, 100);
    EXPECT_LE(test::maxRelDiff(zh, zr), 1e-10) << scheme;
  }
}

TEST(GpDeim, DerivativesMatchFiniteDifferencesAndFormAGradientField) {
  auto hc = test::nlsCase(48, 4, test::comm());
  for (int m : {3, 8, 20}) {
    auto hr = test::gpDeimModel(hc, m);
    const auto d = test::checkDerivatives(*hr);
    EXPECT_LE(d.gradErr, test::kFdTol * d.gradNorm) << "grad H_hr vs FD, m = " << m;
    EXPECT_LE(d.hessErr, test::kFdTol * d.hessNorm) << "Hess H_hr vs FD of grad, m = " << m;
    // A gradient field has a symmetric Jacobian; the FD Jacobian's asymmetry is FD error only.
    EXPECT_LE(d.asym, 1e-7 * d.fdNorm) << "m = " << m;
  }
}

// The reduced-Jacobian rows J_G(y) A (eq:snaps_JG, the DEIM snapshots and GP-ADEIM's F_j) against
// central differences of each row's G_i (weights one-hot on row i), on each rank's own rows; and
// the strided form (row stride ld > 2k, GP-ADEIM's window of several states) writes the same
// numbers and leaves the padding alone.
TEST(GpDeim, ReducedJacobianRowsMatchFiniteDifferences) {
  auto hc = test::nlsCase(32, 4, test::comm());
  ReducedRowKernel kernel(hc.test.system->nonlinearTermPtr(), ownedRowSample(*hc.test.system, *hc.basis.A),
                          Teuchos::null);
  const int r = kernel.reducedDim(), rows = kernel.numRows(), ld = r + 3;
  const DenseVector z = test::probePoint(r);
  kernel.evaluate(z, true, false);
  std::vector<double> J(static_cast<size_t>(rows) * r), wide(static_cast<size_t>(rows) * ld, -7.0);
  kernel.reducedJacobian(J.data());
  kernel.reducedJacobian(wide.data(), ld);
  for (int i = 0; i < rows; ++i)
    for (int c = 0; c < ld; ++c)
      EXPECT_EQ(wide[i * ld + c], c < r ? J[i * r + c] : -7.0) << "row " << i << ", column " << c;
  double err = 0.0, scale = 0.0;
  DenseVector zp(z), zm(z);
  for (int i = 0; i < rows; ++i) {
    std::vector<double> w(rows, 0.0);
    w[i] = 1.0;
    kernel.setWeights(w);
    for (int c = 0; c < r; ++c) {
      zp.assign(z), zm.assign(z);
      zp(c) += test::kFdStep, zm(c) -= test::kFdStep;
      kernel.evaluate(zp, false, false);
      const double gp = kernel.value();
      kernel.evaluate(zm, false, false);
      const double fd = (gp - kernel.value()) / (2 * test::kFdStep);
      err = std::max(err, std::abs(fd - J[i * r + c]));
      scale = std::max(scale, std::abs(J[i * r + c]));
    }
  }
  EXPECT_GT(scale, 0.0);
  EXPECT_LE(err, test::kFdTol * scale);
}

// ||J - J^T|| / ||J|| of the FD Jacobian of a model's vector field at the probe point.
double fieldAsymmetry(DenseHamiltonian& model) {
  const DenseMatrix Jfd = test::fdJacobianOfGradient(model, test::probePoint(model.dim()));
  DenseMatrix asym(Jfd, Teuchos::TRANS);
  asym -= Jfd;
  return asym.normInf() / Jfd.normInf();
}

TEST(GpDeim, ClassicDeimAndSdeimFieldsAreNotGradients) {
  // The same symmetry test that GP-DEIM passes at 1e-7 (FD error ~1e-9) must fail for DEIM of
  // the gradient: its Jacobian B (d grad N_P / dz) is not symmetric. 1e-3 is far above FD error.
  auto hc = test::nlsCase(48, 4, test::comm());
  const auto& sys = *hc.test.system;
  std::vector<RCP<const HamiltonianSystem>> systems{hc.test.system};
  auto tr = Nls1d(48, 5.0).instantiate(test::comm(), {1.0}, true);
  auto states = test::fomSnapshots(tr, "avf", 0.05, 100);
  const auto Ug = gradientDeimBasis({tr.system}, {states}, *hc.basis.A, 48, 1, GradientSnapshots::Projected);
  GradientDeimModel deim(sys, *hc.basis.A, makeGradientDeimPair(*Ug, 12, *hc.basis.A), reduceLinearPart(sys, *hc.basis.A));
  GradientDeimModel sdeim(sys, *hc.basis.A, makeGradientDeimPair(*hc.basis.A, 8, *hc.basis.A),
                          reduceLinearPart(sys, *hc.basis.A));
  EXPECT_GT(fieldAsymmetry(deim), 1e-3) << "classic DEIM";
  EXPECT_GT(fieldAsymmetry(sdeim), 1e-3) << "SDEIM";
  EXPECT_LE(fieldAsymmetry(*test::gpDeimModel(hc, 12)), 1e-7) << "GP-DEIM, same m";
  // The baselines' Jacobian (Newton's matrix) is still right: FD of their field.
  for (DenseHamiltonian* model : {static_cast<DenseHamiltonian*>(&deim), static_cast<DenseHamiltonian*>(&sdeim)}) {
    const DenseVector z = test::probePoint(model->dim());
    DenseMatrix H(model->dim(), model->dim());
    model->addHessian(z, 1.0, H);
    DenseMatrix diff(test::fdJacobianOfGradient(*model, z));
    diff -= H;
    EXPECT_LE(diff.normInf(), test::kFdTol * H.normInf());
  }
}

// The training runs of an nlsCase (eps 0.95 and 1.05): shifted systems and the full model's states.
struct TrainingRuns {
  std::vector<RCP<const HamiltonianSystem>> systems;
  std::vector<RCP<const MultiVector>> states;
};

TrainingRuns nlsTraining(GO n) {
  TrainingRuns t;
  for (double eps : {0.95, 1.05}) {
    auto tr = Nls1d(n, 5.0).instantiate(test::comm(), {eps}, true);
    t.states.push_back(test::fomSnapshots(tr, "avf", 0.05, 100));
    t.systems.push_back(tr.system);
  }
  return t;
}

double frobenius(const MultiVector& X) {
  std::vector<double> norms(X.getNumVectors());
  X.norm2(norms);
  double s = 0.0;
  for (double v : norms) s += v * v;
  return std::sqrt(s);
}

RCP<MultiVector> classicDeimBasis(const TrainingRuns& t, const MultiVector& A, int maxRank, GradientSnapshots kind,
                                  int every = 1) {
  return gradientDeimBasis(t.systems, t.states, A, maxRank, every, kind);
}

// ||a - b|| / ||b|| of the fields (or Hessians) of two models at the probe point.
double fieldDiff(DenseHamiltonian& model, DenseHamiltonian& reference) {
  const int r = reference.dim();
  DenseVector z = test::probePoint(r), g(r), ref(r);
  model.gradient(z, g);
  reference.gradient(z, ref);
  g -= ref;
  return g.normFrobenius() / ref.normFrobenius();
}

double hessianDiff(DenseHamiltonian& model, DenseHamiltonian& reference) {
  const int r = reference.dim();
  const DenseVector z = test::probePoint(r);
  DenseMatrix H(r, r), ref(r, r);
  model.addHessian(z, 1.0, H);
  reference.addHessian(z, 1.0, ref);
  H -= ref;
  return H.normFrobenius() / ref.normFrobenius();
}

// With m = 2n (every state entry sampled) P_g^T U_g is a row permutation of the orthogonal U_g,
// so U_g (P_g^T U_g)^{-1} P_g^T = I and the classic DEIM of full-state snapshots is the Galerkin
// ROM: field and Hessian agree to round-off. 1e-12 relative: cond(P_g^T U_g) = 1 and sums of
// O(n) terms. (The offset A^T g0 - B P_g^T g0 is round-off here; the next test checks it.)
TEST(GpDeim, ClassicDeimOfFullRankIsTheRom) {
  const GO n = 16;
  auto hc = test::nlsCase(n, 4, test::comm());
  const auto& A = *hc.basis.A;
  const auto Ug = classicDeimBasis(nlsTraining(n), A, static_cast<int>(2 * n), GradientSnapshots::Full);
  ASSERT_EQ(Ug->getNumVectors(), static_cast<size_t>(2 * n)) << "the snapshots must span R^{2n} for this test";
  const GradientDeimPair pair = withReferenceGradient(makeGradientDeimPair(*Ug, static_cast<int>(2 * n), A),
                                                      *hc.test.system, A);
  EXPECT_NEAR(pair.conditionNumber, 1.0, 1e-12);
  GradientDeimModel deim(*hc.test.system, A, pair, reduceLinearPart(*hc.test.system, A));
  GalerkinRom rom(hc.test.system, hc.basis.A);
  std::printf("m = 2n: field %.3g, Hessian %.3g relative to the ROM's\n", fieldDiff(deim, rom), hessianDiff(deim, rom));
  EXPECT_LE(fieldDiff(deim, rom), 1e-12);
  EXPECT_LE(hessianDiff(deim, rom), 1e-12);
}

// The shift of Sec. 3.3: full snapshots are grad N(y) - grad N(y0), the model adds grad N(y0)
// back, so at the reference state (z = 0, y = y0) the field is the ROM's for any m, as
// G_s(y0) = 0 makes GP-DEIM exact there. Tolerance 1e-12 relative: F(0) = f_r + A^T g0 +
// (B P^T g0 - B P^T g0), whose cancellation leaves ~eps ||B|| ||P^T g0|| (||B|| ~ cond(P^T U) < 1e2
// here). The projected snapshots (the test parameter eps = 1 is not a training one) interpolate
// grad N(y0) itself with a DEIM error above 1e-6 relative: the two snapshot kinds give different
// models, so an option that picked the wrong one would be seen.
TEST(GpDeim, ClassicDeimOfFullSnapshotsIsExactAtTheReferenceState) {
  const GO n = 48;
  auto hc = test::nlsCase(n, 4, test::comm());
  const auto& A = *hc.basis.A;
  const auto& sys = *hc.test.system;
  GalerkinRom rom(hc.test.system, hc.basis.A);
  const DenseVector z0(rom.dim());
  DenseVector ref(rom.dim()), g(rom.dim());
  rom.gradient(z0, ref);
  const TrainingRuns training = nlsTraining(n);
  const auto full = classicDeimBasis(training, A, 48, GradientSnapshots::Full);
  const auto projected = classicDeimBasis(training, A, 48, GradientSnapshots::Projected);
  for (int m : {4, 12}) {
    const GradientDeimPair pair = makeGradientDeimPair(*full, m, A);
    GradientDeimModel shifted(sys, A, withReferenceGradient(pair, sys, A), reduceLinearPart(sys, A));
    shifted.gradient(z0, g);
    g -= ref;
    const double exact = g.normFrobenius() / ref.normFrobenius();
    GradientDeimModel plain(sys, A, makeGradientDeimPair(*projected, m, A), reduceLinearPart(sys, A));
    plain.gradient(z0, g);
    g -= ref;
    const double interpolated = g.normFrobenius() / ref.normFrobenius();
    std::printf("m = %d: F(0) against the ROM's, full %.3g, projected %.3g (cond(P^T U) %.3g)\n", m, exact,
                interpolated, pair.conditionNumber);
    EXPECT_LE(exact, 1e-12) << "m = " << m;
    EXPECT_GT(interpolated, 1e-6) << "m = " << m;
  }
}

// The textbook snapshots, formed here state by state: grad N(y_s) - grad N(0) of each training
// system at every 10th state of its full-model run (22 snapshots, one of them zero, in R^64). The
// POD keeps up to 64 columns, more than the snapshots' rank, so the full basis spans them exactly:
// the part of S outside span(U_g) is round-off (1e-12 relative: orthonormal U_g, QR-based POD).
// The projected basis (grad N at projected states, unshifted) leaves an O(1e-2) part or more.
TEST(GpDeim, ClassicDeimBasisSpansTheTextbookSnapshots) {
  const GO n = 32;
  auto hc = test::nlsCase(n, 4, test::comm());
  const TrainingRuns training = nlsTraining(n);
  const int every = 10, perRun = 11;
  MultiVector S(training.systems[0]->map(), 2 * perRun);
  Vector zero(training.systems[0]->map()), g0(training.systems[0]->map());
  for (size_t j = 0; j < 2; ++j) {
    training.systems[j]->nonlinearGradient(zero, g0);
    for (int c = 0; c < perRun; ++c) {
      auto col = S.getVectorNonConst(j * perRun + c);
      training.systems[j]->nonlinearGradient(*training.states[j]->getVector(c * every), *col);
      col->update(-1.0, g0, 1.0);
    }
  }
  const double sNorm = frobenius(S);
  for (GradientSnapshots kind : {GradientSnapshots::Full, GradientSnapshots::Projected}) {
    const auto Ug = classicDeimBasis(training, *hc.basis.A, static_cast<int>(2 * n), kind, every);
    auto local = rcp(new Map(Ug->getNumVectors(), 0, test::comm(), Tpetra::LocallyReplicated));
    MultiVector C(local, S.getNumVectors()), R(S, Teuchos::Copy);
    C.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, *Ug, S, 0.0);
    R.multiply(Teuchos::NO_TRANS, Teuchos::NO_TRANS, -1.0, *Ug, C, 1.0);
    const double outside = frobenius(R) / sNorm;
    const bool full = kind == GradientSnapshots::Full;
    std::printf("%s snapshots: %zu vectors, ||(I - U U^T) S|| / ||S|| = %.3g\n", full ? "full" : "projected",
                Ug->getNumVectors(), outside);
    if (full)
      EXPECT_LE(outside, 1e-12);
    else
      EXPECT_GT(outside, 1e-3);
  }
}

TEST(GpDeim, AvfConservesHyperReducedHamiltonian) {
  auto hc = test::nlsCase(48, 4, test::comm());
  for (int m : {4, 8, 16, 48}) {  // 48 = d
    auto hr = test::gpDeimModel(hc, m);
    EXPECT_LE(test::avfDriftBeyondBound(*hr, 0.05, 1000), 0.0)
        << "m = " << m << ": |H_hr(z_j) - H_hr(z_0)| exceeds the AVF bound";
  }
}

TEST(GpDeim, LaggedJacobianNewtonGivesTheSameTrajectoryWithFewerFactorisations) {
  // Both solve every step to ||R|| <= 1e-12; the solutions then differ by at most ~ ||K^{-1}||
  // 1e-12 per step, accumulated over 200 steps of a stable scheme: 1e-9 relative is the
  // bound asserted.
  auto hc = test::nlsCase(48, 4, test::comm());
  auto hr = test::gpDeimModel(hc, 16);
  GalerkinRom rom(hc.test.system, hc.basis.A);
  for (DenseHamiltonian* model : {static_cast<DenseHamiltonian*>(hr.get()), static_cast<DenseHamiltonian*>(&rom)}) {
    auto full = test::denseIntegrator("avf"), lagged = test::denseIntegrator("avf");
    lagged.set("jacobianLag", true);
    std::vector<DenseVector> za, zb;
    DenseModelIntegrator ia(*model, full, 4), ib(*model, lagged, 4);
    DenseVector z(model->dim());
    const RunStats sa = ia.run(z, 0.05, 200, [&](long, double, const DenseVector& zj, const StepReport&) { za.push_back(zj); });
    z.putScalar(0.0);
    const RunStats sb = ib.run(z, 0.05, 200, [&](long, double, const DenseVector& zj, const StepReport&) { zb.push_back(zj); });
    EXPECT_LE(test::maxRelDiff(zb, za), 1e-9);
    EXPECT_EQ(sa.newtonMatrices, sa.newtonIterations) << "full Newton factors at every iteration";
    EXPECT_LT(sb.newtonMatrices, sa.newtonMatrices / 4) << "lagged: " << sb.newtonMatrices << " vs " << sa.newtonMatrices;
    EXPECT_EQ(ib.backend().newtonMatrixAssemblies(), sb.newtonMatrices) << "the count is the backend's LU count";
  }
}

TEST(GpDeim, OnlineObjectDoesNotGrowWithN) {
  std::vector<size_t> held, entries;
  std::vector<LO> rows;
  for (GO nx : {32, 64, 128}) {
    Swe2d scene(nx);
    auto hc = test::sceneCase(scene, {{1.2, 0.5}, {1.8, 1.0}}, {1.5, 0.8}, 4, 0.01, 10, test::comm(), 40);
    auto hr = test::gpDeimModel(hc, 12);
    held.push_back(hr->numbersHeld());
    entries.push_back(hr->stencilEntries());
    rows.push_back(hr->kernelRowsPerEvaluation());
  }
  for (size_t i = 1; i < held.size(); ++i) {
    EXPECT_EQ(held[i], held[0]) << "numbers held online";
    EXPECT_EQ(entries[i], entries[0]) << "stencil entries";
    EXPECT_EQ(rows[i], rows[0]) << "kernel rows per evaluation";
  }
  EXPECT_EQ(rows[0], 12);
  EXPECT_EQ(entries[0], 12u * 5u);  // the SWE stencil has 5 entries
}

TEST(GpDeim, ExtremeSizesRunOrFailClearly) {
  auto hc = test::nlsCase(32, 1, test::comm());  // 2k = 2
  for (int m : {1, 2}) {                          // m = 1, m = 2k
    auto hr = test::gpDeimModel(hc, m);
    const auto z = test::trajectory(*hr, "avf", 0.05, 50);
    for (const auto& zj : z)
      for (int i = 0; i < zj.length(); ++i) ASSERT_TRUE(std::isfinite(zj(i))) << "m = " << m;
  }
  // m beyond the DEIM basis: a clear error naming m and what is available.
  const int tooMany = static_cast<int>(hc.deim.U->getNumVectors()) + 1;
  try {
    test::gpDeimModel(hc, tooMany);
    FAIL() << "m = " << tooMany << " was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("m = " + std::to_string(tooMany)), std::string::npos) << e.what();
  }
}

TEST(GpDeim, LinearProblemHasNothingToHyperReduce) {
  // eps = 0: G = 0, every reduced-Jacobian snapshot is zero.
  Nls1d scene(32);
  try {
    test::sceneCase(scene, {{0.0}}, {0.0}, 2, 0.05, 20, test::comm());
    FAIL() << "an all-zero snapshot set was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("all zero"), std::string::npos) << e.what();
  }
}

// One AVF training run at mu = 1 (dt = 0.05) and its PSD basis of size 2k.
struct TrainedBasis {
  SceneInstance tr;
  RCP<const MultiVector> snaps;
  ReducedBasis basis;
};
TrainedBasis trainedBasis(const Nls1d& scene, long steps, int k) {
  auto tr = scene.instantiate(test::comm(), {1.0}, true);
  auto snaps = test::fomSnapshots(tr, "avf", 0.05, steps);
  BasisOptions opt;
  opt.k = k;
  auto basis = computeSymplecticBasis({snaps}, tr.system->space(), opt);
  return {tr, snaps, basis};
}

TEST(GpDeim, RandomizedDeimBasisMatchesTheExactOne) {
  // NLS reduced-Jacobian snapshots decay fast: the range finder with 10 extra columns and one
  // power pass resolves the leading singular values to a relative error of order
  // (sigma_{m+11} / sigma_j)^4 (HMT11 Cor. 10.10), here < 1e-6; the leading subspace likewise.
  const auto [tr, snaps, basis] = trainedBasis(Nls1d(64, 5.0), 60, 4);
  DeimBasisOptions opt;
  opt.maxRank = 20;
  const auto exact = computeDeimBasis({tr.system}, {snaps}, *basis.A, opt);
  opt.svd = "randomized";
  const auto rnd = computeDeimBasis({tr.system}, {snaps}, *basis.A, opt);
  ASSERT_GE(rnd.singularValues.size(), 10u);
  for (size_t j = 0; j < 10; ++j)
    EXPECT_NEAR(rnd.singularValues[j], exact.singularValues[j], 1e-6 * exact.singularValues[j]) << "j = " << j;
  // The leading 8 vectors span the same space: ||U_e^T U_r||_F^2 = 8 up to the same order.
  auto local = rcp(new Map(8, 0, test::comm(), Tpetra::LocallyReplicated));
  MultiVector C(local, 8);
  C.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, *exact.U->subView(Teuchos::Range1D(0, 7)),
             *rnd.U->subView(Teuchos::Range1D(0, 7)), 0.0);
  std::vector<double> norms(8);
  C.norm2(Teuchos::ArrayView<double>(norms));
  double f2 = 0.0;
  for (double x : norms) f2 += x * x;
  EXPECT_NEAR(f2, 8.0, 1e-6);
}

TEST(GpDeim, RandomizedQrProjectionResolvesBelowTheGramFloor) {
  // maxRank = d = 64: the exact route truncates nothing, and the range finder (ell = min(d,
  // maxRank + 10) = d columns) spans all of R^d, so B = Q^T M_J has exactly M_J's singular values.
  // The Gram route (B B^T) resolves them only to ~1e-7 sigma_1 and cuts there (41 of 64 kept);
  // the QR route (R of the stacked B^T) is backward stable: measured |error| <= 1.9e-15 sigma_1,
  // so 1e-12 sigma_1 leaves three decades of margin.
  const auto [tr, snaps, basis] = trainedBasis(Nls1d(64, 5.0), 60, 4);
  DeimBasisOptions opt;
  opt.maxRank = 64;
  const auto exact = computeDeimBasis({tr.system}, {snaps}, *basis.A, opt);
  opt.svd = "randomized";
  opt.powerIterations = 0;  // a power pass squares the spectrum: its orth would cut at sqrt(eps) too
  const auto gram = computeDeimBasis({tr.system}, {snaps}, *basis.A, opt);
  opt.gramProjection = false;
  const auto qr = computeDeimBasis({tr.system}, {snaps}, *basis.A, opt);
  const double s1 = exact.singularValues[0];
  size_t resolved = 0;  // exact values above 1e-10 sigma_1: far below the Gram floor
  while (resolved < exact.singularValues.size() && exact.singularValues[resolved] > 1e-10 * s1) ++resolved;
  ASSERT_GE(qr.singularValues.size(), resolved);
  for (size_t j = 0; j < resolved; ++j)
    EXPECT_NEAR(qr.singularValues[j], exact.singularValues[j], 1e-12 * s1) << "j = " << j;
  EXPECT_LT(gram.singularValues.size(), resolved) << "the Gram route was expected to stop near 1e-7 sigma_1";
  EXPECT_GT(exact.singularValues[gram.singularValues.size()], 1e-10 * s1);
  // U = Q W: without a power pass Q spans the sketch M_J Omega, not M_J's singular vectors, so W
  // is far from the identity and U's columns come out right only if W is applied right. The
  // leading vectors of well-separated sigma's are determined to ~eps sigma_1 / gap (Wedin):
  // |u_exact_j . u_qr_j| = 1 to 1e-8 where the relative gap to both neighbours exceeds 1e-3
  // (eps (sigma_1 / sigma_j) / 1e-3 <= 1e-10 for the leading ones; measured within 1e-15).
  int checked = 0;
  for (size_t j = 0; j + 1 < resolved && checked < 6; ++j) {
    const double* sv = exact.singularValues.data();
    const double gap = std::min(sv[j] - sv[j + 1], j > 0 ? sv[j - 1] - sv[j] : sv[j]) / sv[j];
    if (gap < 1e-3) continue;
    ++checked;
    EXPECT_NEAR(std::abs(exact.U->getVector(j)->dot(*qr.U->getVector(j))), 1.0, 1e-8) << "j = " << j;
  }
  EXPECT_GE(checked, 4) << "too few separated singular values to check the vectors";
}

int podSteps(const DeimBasis& b) { return b.podSteps.total(); }

// M_J's SVD for the hierarchical-POD tests: maxRank = d = 64 and all snapshots in one chunk.
DeimBasis svdOfSnapshots(const TrainedBasis& t, DeimBasisOptions& opt) {
  opt.maxRank = 64;
  opt.chunkSnapshots = 100000;
  return computeDeimBasis({t.tr.system}, {t.snaps}, *t.basis.A, opt);
}

// M_J (eq:snaps_JG) stacked here without the offline machinery (no snapshot set, stride, chunk or
// POD): for every every-th training state y_s, z = A^T y_s and the kernel's rows J_G(y0 + A z) A
// (checked against finite differences above), d x (N_s 2k) column-major; its LAPACK singular values.
std::vector<double> denseSnapshotSingularValues(const TrainedBasis& t, int every) {
  ReducedRowKernel kernel(t.tr.system->nonlinearTermPtr(), ownedRowSample(*t.tr.system, *t.basis.A),
                          Teuchos::null);
  const int r = kernel.reducedDim(), d = kernel.numRows(), states = static_cast<int>(t.snaps->getNumVectors());
  const std::vector<double> Z = test::transposeTimes(*t.basis.A, *t.snaps);  // r x states, row-major
  std::vector<double> M, J(static_cast<size_t>(d) * r);
  DenseVector z(r);
  for (int s = 0; s < states; s += every) {
    for (int i = 0; i < r; ++i) z(i) = Z[static_cast<size_t>(i) * states + s];
    kernel.evaluate(z, true, false);
    kernel.reducedJacobian(J.data());
    for (int c = 0; c < r; ++c)
      for (int i = 0; i < d; ++i) M.push_back(J[static_cast<size_t>(i) * r + c]);
  }
  const int cols = static_cast<int>(M.size()) / d;
  std::vector<double> sv(std::min(d, cols)), dummy(1), work(1);
  Teuchos::LAPACK<int, double> lapack;
  int info = 0;
  lapack.GESVD('N', 'N', d, cols, M.data(), d, sv.data(), dummy.data(), 1, dummy.data(), 1, work.data(), -1,
               nullptr, &info);
  work.resize(static_cast<size_t>(work[0]));
  lapack.GESVD('N', 'N', d, cols, M.data(), d, sv.data(), dummy.data(), 1, dummy.data(), 1, work.data(),
               static_cast<int>(work.size()), nullptr, &info);
  EXPECT_EQ(info, 0);
  return sv;
}

TEST(GpDeim, DeimBasisSingularValuesAreThoseOfTheStackedReducedJacobians) {
  // The DEIM basis's singular values against a dense SVD of M_J formed above, for every state and
  // for every 3rd (the stride picks states 0, 3, ...). maxRank = d truncates nothing; a backward-
  // stable SVD per POD step keeps sigma_j to a few eps sigma_1 per step (~20 steps): 1e-12 sigma_1.
  // A skipped, repeated or mis-strided state, or rows of another state, changes the spectrum
  // far beyond that. The dense reference is formed on one rank (the kernel's rows are local).
  if (test::comm()->getSize() > 1) GTEST_SKIP() << "the dense reference stacks one rank's rows";
  const TrainedBasis t = trainedBasis(Nls1d(64, 5.0), 60, 4);
  for (int every : {1, 3}) {
    DeimBasisOptions opt;
    opt.snapshotEvery = every;
    const auto b = svdOfSnapshots(t, opt);
    const std::vector<double> dense = denseSnapshotSingularValues(t, every);
    EXPECT_EQ(b.snapshots, (static_cast<long>(t.snaps->getNumVectors()) + every - 1) / every);
    const double s1 = dense[0];
    size_t resolved = 0;
    while (resolved < dense.size() && dense[resolved] > 1e-10 * s1) ++resolved;
    ASSERT_GT(resolved, 20u);
    ASSERT_GE(b.singularValues.size(), resolved);
    for (size_t j = 0; j < resolved; ++j)
      EXPECT_NEAR(b.singularValues[j], dense[j], 1e-12 * s1) << "every " << every << ", j = " << j;
  }
}

// The hierarchical POD against the streaming POD of all snapshots at once (whose singular values
// are those of the dense M_J: the test above).
TEST(GpDeim, HierarchicalPodWithoutTruncationIsTheSvd) {
  // maxRank = d: no chunk and no root truncates beyond the numerical rank, so the hierarchical POD
  // (11 chunks of 6 snapshots, then the root) and one streaming POD of all snapshots (one chunk)
  // both give M_J's singular values; a backward-stable SVD per step keeps them to a few eps
  // sigma_1 per step (~20 steps here): 1e-12 sigma_1 is a margin of ~20x over that.
  const TrainedBasis t = trainedBasis(Nls1d(64, 5.0), 60, 4);
  DeimBasisOptions opt;
  const auto plain = svdOfSnapshots(t, opt);
  opt.chunkSnapshots = 6;
  const auto hier = computeDeimBasis({t.tr.system}, {t.snaps}, *t.basis.A, opt);
  const double s1 = plain.singularValues[0];
  size_t resolved = 0;  // above the chunks' own rank floor (their columns x eps x their sigma_1)
  while (resolved < plain.singularValues.size() && plain.singularValues[resolved] > 1e-10 * s1) ++resolved;
  ASSERT_GE(hier.singularValues.size(), resolved);
  ASSERT_GT(resolved, 20u);
  for (size_t j = 0; j < resolved; ++j) EXPECT_NEAR(hier.singularValues[j], plain.singularValues[j], 1e-12 * s1) << j;
  EXPECT_NEAR(hier.energy, plain.energy, 1e-12 * plain.energy);
  EXPECT_EQ(hier.snapshots, plain.snapshots);
}

TEST(GpDeim, HierarchicalPodBoundedByItsTruncations) {
  // With maxRank = 12 < rank(M_J) every step may drop singular directions. A step's input
  // [Z, X] has Z Z^T <= (the columns it stands for) (...)^T, so each dropped sigma^2 is at most
  // sigma_13(M_J)^2, and the Gram matrices differ by at most (steps) sigma_13^2 in the 2-norm
  // (HAPOD, Himpe, Leibner & Rave 2018, Thm. 3.1); by Weyl, |sigma_j^2 - sigma_hat_j^2| is
  // bounded by the same. Checked for the plain streaming POD (one chunk) and the hierarchical one.
  const TrainedBasis t = trainedBasis(Nls1d(64, 5.0), 60, 4);
  DeimBasisOptions opt;
  const auto exact = svdOfSnapshots(t, opt);
  ASSERT_GT(exact.singularValues.size(), 13u);
  const double s13 = exact.singularValues[12], s1 = exact.singularValues[0];
  opt.maxRank = 12;
  for (int chunk : {100000, 6}) {
    opt.chunkSnapshots = chunk;
    const auto b = computeDeimBasis({t.tr.system}, {t.snaps}, *t.basis.A, opt);
    ASSERT_EQ(b.singularValues.size(), 12u);
    const double bound = podSteps(b) * s13 * s13 + 1e-12 * s1 * s1;  // + the round-off of the steps
    for (size_t j = 0; j < 12; ++j) {
      const double se = exact.singularValues[j], sh = b.singularValues[j];
      EXPECT_LE(std::abs(se * se - sh * sh), bound) << "chunkSnapshots " << chunk << ", j = " << j;
      // Z Z^T <= M_J M_J^T after every truncation: no sigma grows (to the steps' round-off).
      EXPECT_LE(sh, se + 1e-13 * s1) << "a truncated POD cannot exceed M_J's singular values";
    }
  }
}

// The step counts the basis reports (stages.csv, the HAPOD bound above) count each POD step once:
// one chunk of N snapshots in blocks of 5 takes ceil(N / 5) steps; chunks of 6 take ceil(6 / 5)
// each (the last ceil(rest / 5)) and the root one per chunk (a chunk's rank <= maxRank columns).
TEST(GpDeim, PodStepsCountEachStepOnce) {
  const TrainedBasis t = trainedBasis(Nls1d(64, 5.0), 60, 4);
  DeimBasisOptions opt;
  opt.maxRank = 12;
  opt.blockSnapshots = 5;
  opt.chunkSnapshots = 100000;
  const auto one = computeDeimBasis({t.tr.system}, {t.snaps}, *t.basis.A, opt);
  ASSERT_GT(one.snapshots, 12);
  EXPECT_EQ(podSteps(one), (one.snapshots + 4) / 5);
  opt.chunkSnapshots = 6;
  const auto hier = computeDeimBasis({t.tr.system}, {t.snaps}, *t.basis.A, opt);
  long expected = 0;
  for (long first = 0; first < hier.snapshots; first += 6) expected += (std::min(6L, hier.snapshots - first) + 4) / 5 + 1;
  EXPECT_EQ(podSteps(hier), expected);
}

TEST(GpDeim, DuplicatedSnapshotsGiveTheSameDeimPair) {
  const auto [tr, snaps, basis] = trainedBasis(Nls1d(32), 40, 3);
  DeimBasisOptions dopt;
  dopt.maxRank = 32;
  const auto once = computeDeimBasis({tr.system}, {snaps}, *basis.A, dopt);
  const auto twice = computeDeimBasis({tr.system, tr.system}, {snaps, snaps}, *basis.A, dopt);
  // Duplicating every snapshot scales M_J M_J^T by 2: sigma by sqrt(2), same subspace.
  ASSERT_EQ(once.singularValues.size(), twice.singularValues.size());
  for (size_t j = 0; j < std::min<size_t>(10, once.singularValues.size()); ++j)
    EXPECT_NEAR(twice.singularValues[j], std::sqrt(2.0) * once.singularValues[j], 1e-10 * once.singularValues[0]);
  const int m = 8;
  EXPECT_EQ(selectDeimIndices(*once.U, m), selectDeimIndices(*twice.U, m));
}

}  // namespace
