// Embedding GPHR in a user's Tpetra code with a Hamiltonian of its own: the periodic
// Fermi-Pasta-Ulam-beta lattice
//   H(q, p) = sum_i p_i^2 / 2 + sum_i (q_{i+1} - q_i)^2 / 2 + beta/4 sum_i (q_{i+1} - q_i)^4,
// decomposed as in the paper's eq:decomp: L = blockdiag(K, I) with K the periodic stiffness
// matrix, and G_i = beta/4 (q_{i+1} - q_i)^4 with stencil (q_i, q_{i+1}), v = 1.
// The user writes only the row kernel, L and y0; GPHR assembles gradients and Hessians and
// integrates with AVF. Then the lattice is hyper-reduced in a few calls (the paper's GP-DEIM):
// shift, snapshots, symplectic basis, reduced-Jacobian DEIM basis, GP-DEIM model, AVF again.
// Exit code 0 iff AVF conserves H (full model) and H_hr (hyper-reduced model) to 1e-9 relative
// and the hyper-reduced trajectory stays within 1e-2 of the full one.
#include <Tpetra_Core.hpp>
#include <cmath>
#include <cstdio>

#include "gphr/core/HamiltonianSystem.hpp"
#include "gphr/hyper/DeimBasis.hpp"
#include "gphr/hyper/GpDeimModel.hpp"
#include "gphr/reduction/SymplecticBasis.hpp"
#include "gphr/timeint/DenseModelIntegrator.hpp"
#include "gphr/timeint/FullModelIntegrator.hpp"

struct FpuKernel {
  double beta;
  KOKKOS_INLINE_FUNCTION
  void operator()(gphr::GO, const double* y, double& g, double* grad, double* hess) const {
    const double d = y[1] - y[0];  // q_{i+1} - q_i
    g = 0.25 * beta * d * d * d * d;
    if (grad) {
      grad[1] = beta * d * d * d;
      grad[0] = -grad[1];
    }
    if (hess) {
      const double h = 3 * beta * d * d;
      hess[0] = hess[3] = h;
      hess[1] = hess[2] = -h;
    }
  }
};

int main(int argc, char** argv) {
  Tpetra::ScopeGuard scope(&argc, &argv);
  using namespace gphr;
  auto comm = Tpetra::getDefaultComm();
  const GO n = 200;
  const double beta = 0.5;
  auto space = rcp(new PhaseSpace(n, comm));
  const auto& map = space->map();
  auto L = rcp(new CrsMatrix(map, 3));
  auto y0 = rcp(new Vector(map));
  Stencil stencil;
  {
    auto y = y0->getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (LO il = 0; il < space->numLocalDofs(); ++il) {
      const GO i = space->firstLocalDof() + il, im = (i + n - 1) % n, ip = (i + 1) % n;
      L->insertGlobalValues(i, Teuchos::tuple<GO>(im, i, ip), Teuchos::tuple<double>(-1.0, 2.0, -1.0));
      L->insertGlobalValues(n + i, Teuchos::tuple<GO>(n + i), Teuchos::tuple<double>(1.0));
      const double x = (static_cast<double>(i) - n / 2) / 6.0;
      y(il, 0) = 3.0 * std::exp(-x * x);  // q: a pulse steep enough for the quartic term to matter
      y(space->numLocalDofs() + il, 0) = 0.0;
      stencil.gids.push_back(i);
      stencil.gids.push_back(ip);
      stencil.offsets.push_back(stencil.gids.size());
    }
  }
  L->fillComplete(map, map);
  auto v = rcp(new Vector(space->dofMap()));
  v->putScalar(1.0);
  auto term = makeRowKernelTerm(FpuKernel{beta}, space->dofMap(), map, std::move(stencil), v, 4);
  auto system = rcp(new HamiltonianSystem(space, L, rcp(new Vector(map)), 0.0, term));

  Teuchos::ParameterList integrator("integrator");
  integrator.set("scheme", "avf").set("newtonTolerance", 1e-12);
  FullModelIntegrator avf(system, integrator);
  Vector y(*y0, Teuchos::Copy);
  const double H0 = system->hamiltonian(y);
  double drift = 0.0;
  const RunStats stats = avf.run(y, 0.05, 400, [&](long, double, const Vector& yj, const StepReport&) {
    drift = std::max(drift, std::abs(system->hamiltonian(yj) - H0));
  });
  bool ok = drift <= 1e-9 * std::abs(H0);
  if (comm->getRank() == 0)
    std::printf("FPU-beta lattice, n = %lld, %d rank(s): %ld AVF steps, %.2f Newton/step, "
                "max |H - H0| / |H0| = %.2e -> %s\n",
                static_cast<long long>(n), comm->getSize(), stats.steps,
                double(stats.newtonIterations) / stats.steps, drift / std::abs(H0), ok ? "ok" : "FAILED");

  // --- GP-DEIM of the same lattice ---
  auto shifted = system->shifted(*y0);  // eq:shiftH: the state y - y0 starts at 0
  FullModelIntegrator fom(shifted, integrator);
  Vector ys(map);
  auto snapshots = rcp(new MultiVector(map, 401));
  fom.run(ys, 0.05, 400, [&](long j, double, const Vector& yj, const StepReport&) {
    Tpetra::deep_copy(*snapshots->getVectorNonConst(j), yj);
  });
  BasisOptions basisOptions;
  basisOptions.k = 8;
  const ReducedBasis basis = computeSymplecticBasis({snapshots}, *space, basisOptions);
  const DeimBasis deim = computeDeimBasis({shifted}, {snapshots}, *basis.A, DeimBasisOptions());
  const int m = 24;
  auto hr = buildGpDeimModel(*shifted, *basis.A, *deim.U, m);
  DenseModelIntegrator hrAvf(*hr, integrator, 4);
  DenseVector z(hr->dim());
  const double Hhr0 = hr->hamiltonian(z);
  double hrDrift = 0.0, err = 0.0, ref = 0.0;
  Vector yhr(map);
  MultiVector zmv(rcp(new Map(hr->dim(), 0, comm, Tpetra::LocallyReplicated)), 1);
  hrAvf.run(z, 0.05, 400, [&](long j, double, const DenseVector& zj, const StepReport&) {
    hrDrift = std::max(hrDrift, std::abs(hr->hamiltonian(zj) - Hhr0));
    auto zv = zmv.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (int i = 0; i < zj.length(); ++i) zv(i, 0) = zj(i);
    yhr.multiply(Teuchos::NO_TRANS, Teuchos::NO_TRANS, 1.0, *basis.A, zmv, 0.0);  // y - y0 = A z
    yhr.update(-1.0, *snapshots->getVector(j), 1.0);
    err = std::max(err, yhr.norm2());
    ref = std::max(ref, snapshots->getVector(j)->norm2() + y0->norm2());
  });
  const bool hrOk = hrDrift <= 1e-9 * std::abs(Hhr0) && err <= 1e-2 * ref;
  if (comm->getRank() == 0)
    std::printf("GP-DEIM: 2k = %d, m = %d of d = %lld rows: max |H_hr - H_hr0| / |H_hr0| = %.2e, "
                "max ||y - y_hr|| / ||y|| = %.2e -> %s\n",
                hr->dim(), m, static_cast<long long>(n), hrDrift / std::abs(Hhr0), err / ref, hrOk ? "ok" : "FAILED");
  ok = ok && hrOk;
  return ok ? 0 : 1;
}
