#include <cmath>

#include "gphr/core/Error.hpp"
#include "gphr/models/Scene.hpp"

namespace gphr {

namespace {
// Row kernel of the 2D SWE at grid point i: stencil (chi_i, Phi_E, Phi_W, Phi_N, Phi_S),
// a = (D1 Phi)_i = (Phi_E - Phi_W) / (2 dx), b = (D2 Phi)_i = (Phi_N - Phi_S) / (2 dx),
// G_i = gamma/2 chi_i (a^2 + b^2).
struct SweKernel {
  double gamma, h;  // h = 1 / (2 dx)
  KOKKOS_INLINE_FUNCTION
  void operator()(GO, const Scalar* y, Scalar& g, Scalar* grad, Scalar* hess) const {
    const Scalar chi = y[0], a = h * (y[1] - y[2]), b = h * (y[3] - y[4]);
    g = 0.5 * gamma * chi * (a * a + b * b);
    if (grad) {
      grad[0] = 0.5 * gamma * (a * a + b * b);
      grad[1] = gamma * chi * a * h;
      grad[2] = -grad[1];
      grad[3] = gamma * chi * b * h;
      grad[4] = -grad[3];
    }
    if (hess) {
      for (int k = 0; k < 25; ++k) hess[k] = 0.0;
      const Scalar ca = gamma * a * h, cb = gamma * b * h, cc = gamma * chi * h * h;
      // d/dchi d/dPhi
      hess[0 * 5 + 1] = hess[1 * 5 + 0] = ca;
      hess[0 * 5 + 2] = hess[2 * 5 + 0] = -ca;
      hess[0 * 5 + 3] = hess[3 * 5 + 0] = cb;
      hess[0 * 5 + 4] = hess[4 * 5 + 0] = -cb;
      // d^2/dPhi^2: chi gamma h^2 [[1,-1],[-1,1]] per direction
      hess[1 * 5 + 1] = hess[2 * 5 + 2] = hess[3 * 5 + 3] = hess[4 * 5 + 4] = cc;
      hess[1 * 5 + 2] = hess[2 * 5 + 1] = hess[3 * 5 + 4] = hess[4 * 5 + 3] = -cc;
    }
  }
};
}  // namespace

Swe2d::Swe2d(GO nx, double halfLength) : nx_(nx), L_(halfLength) {
  GPHR_REQUIRE(nx >= 3, InputError, "swe2d: nx = ", nx,
               " is not allowed: nx must be >= 3 (the centered stencil needs distinct neighbours)");
  GPHR_REQUIRE(halfLength > 0, InputError, "swe2d: half length ", halfLength, " must be > 0");
  box_.names = {"beta", "gamma"};
  box_.bounds = {{1.1, 1.7}, {0.7, 1.3}};
  box_.enters = {EntersInitialState, EntersRowKernel | EntersLinearPart};
}

std::optional<SceneGrid> Swe2d::grid() const {
  const double dx = 2 * L_ / nx_;  // as in build(): point a + nx b at (-L + a dx, -L + b dx), periodic
  return SceneGrid{{nx_, nx_}, {-L_, -L_}, {dx, dx}, {"chi", "Phi"}, false};
}

RCP<const RowEvaluator> Swe2d::rowKernel(const std::vector<double>& mu) const {
  GPHR_REQUIRE(mu.size() == 2, InputError, "swe2d takes two parameters (beta, gamma), got ", mu.size());
  const double dx = 2 * L_ / nx_;  // as in build(): the same h to the last bit
  return makeRowEvaluator(SweKernel{mu[1], 0.5 / dx}, 3, 5);  // chi_i and Phi at E, W, N, S
}

std::pair<RCP<HamiltonianSystem>, RCP<Vector>> Swe2d::build(const RCP<const Comm>& comm,
                                                           const std::vector<double>& mu) const {
  return assemble(nullptr, comm, mu);
}

std::pair<RCP<HamiltonianSystem>, RCP<Vector>> Swe2d::rebuild(const HamiltonianSystem& like,
                                                             const std::vector<double>& mu) const {
  GPHR_REQUIRE(like.space().n() == nx_ * nx_ && like.nonlinearTerm().maxStencilSize() == 5, InputError,
               "swe2d: a system of n = ", like.space().n(), " and stencils of ", like.nonlinearTerm().maxStencilSize(),
               " entries cannot lend its layout to this scene (n = nx^2 = ", nx_ * nx_, ", stencils of 5)");
  return assemble(&like, like.space().comm(), mu);
}

std::pair<RCP<HamiltonianSystem>, RCP<Vector>> Swe2d::assemble(const HamiltonianSystem* like,
                                                              const RCP<const Comm>& comm,
                                                              const std::vector<double>& mu) const {
  GPHR_REQUIRE(mu.size() == 2, InputError, "swe2d takes two parameters (beta, gamma), got ", mu.size());
  const double beta = mu[0], gamma = mu[1], dx = 2 * L_ / nx_;
  const GO n = nx_ * nx_;
  const RCP<const PhaseSpace> space = like ? like->spacePtr() : rcp<const PhaseSpace>(new PhaseSpace(n, comm));
  const auto& map = space->map();
  // L = blockdiag(gamma I, 0): the chi^2 part of H. On like's graph the values replace the zeros
  // of a matrix on that (static) graph.
  auto L = like ? rcp(new CrsMatrix(like->linearPart().getCrsGraph())) : rcp(new CrsMatrix(map, 1));
  auto y0 = rcp(new Vector(map));
  Stencil st;
  {
    auto yv = y0->getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (LO il = 0; il < space->numLocalDofs(); ++il) {
      const GO i = space->firstLocalDof() + il, a = i % nx_, b = i / nx_;
      if (like) L->replaceGlobalValues(i, Teuchos::tuple<GO>(i), Teuchos::tuple<Scalar>(gamma));
      else L->insertGlobalValues(i, Teuchos::tuple<GO>(i), Teuchos::tuple<Scalar>(gamma));
      const double x1 = -L_ + a * dx, x2 = -L_ + b * dx;
      yv(il, 0) = 1.0 + 0.5 * std::exp(-beta * (x1 * x1 + x2 * x2));
      yv(space->numLocalDofs() + il, 0) = 0.0;
      if (like) continue;
      auto id = [&](GO aa, GO bb) { return n + ((aa + nx_) % nx_) + nx_ * ((bb + nx_) % nx_); };
      for (GO g : {i, id(a + 1, b), id(a - 1, b), id(a, b + 1), id(a, b - 1)}) st.gids.push_back(g);
      st.offsets.push_back(st.gids.size());
    }
  }
  L->fillComplete(map, map);
  const SweKernel kernel{gamma, 0.5 / dx};
  RCP<const NonlinearTerm> term;
  if (like) {
    term = makeRowKernelTerm(kernel, like->nonlinearTerm(), 3);
  } else {
    auto v = rcp(new Vector(space->dofMap()));
    v->putScalar(1.0);
    term = makeRowKernelTerm(kernel, space->dofMap(), map, std::move(st), v, 3);
  }
  auto system = rcp(new HamiltonianSystem(space, L, rcp(new Vector(map)), 0.0, term));
  return {system, y0};
}

}  // namespace gphr
