#include <cmath>

#include "gphr/core/Error.hpp"
#include "gphr/models/Scene.hpp"

namespace gphr {

namespace {
// Row kernel of the NLS: stencil (q_i, p_i), G_i = -eps/4 (q_i^2 + p_i^2)^2.
struct NlsKernel {
  double eps;
  KOKKOS_INLINE_FUNCTION
  void operator()(GO, const Scalar* y, Scalar& g, Scalar* grad, Scalar* hess) const {
    const Scalar q = y[0], p = y[1], r = q * q + p * p;
    g = -0.25 * eps * r * r;
    if (grad) {
      grad[0] = -eps * r * q;
      grad[1] = -eps * r * p;
    }
    if (hess) {
      hess[0] = -eps * (3 * q * q + p * p);
      hess[1] = hess[2] = -2 * eps * q * p;
      hess[3] = -eps * (q * q + 3 * p * p);
    }
  }
};
}  // namespace

Nls1d::Nls1d(GO n, double halfLength, bool pulseParameters) : n_(n), L_(halfLength), pulse_(pulseParameters) {
  GPHR_REQUIRE(n >= 3, InputError, "nls1d: n = ", n, " is not allowed: n must be >= 3");
  GPHR_REQUIRE(halfLength > 0, InputError, "nls1d: half length ", halfLength, " must be > 0");
  box_.names = {"eps"};
  box_.bounds = {{0.9, 1.1}};
  box_.enters = {EntersRowKernel};
  if (!pulse_) return;
  // the pulse u0 = a sqrt(2) sech(x) e^{i c x}: its amplitude a and velocity c (the paper's a = 1,
  // c = 1/2 at the box's centre), both in the initial state only
  box_.names.insert(box_.names.end(), {"amplitude", "velocity"});
  box_.bounds.insert(box_.bounds.end(), {{0.8, 1.2}, {0.3, 0.7}});
  box_.enters.insert(box_.enters.end(), {EntersInitialState, EntersInitialState});
}

std::optional<SceneGrid> Nls1d::grid() const {
  const double dx = 2 * L_ / n_;  // as in build(): x_i = -L + i dx, periodic (x = L is x = -L)
  return SceneGrid{{n_}, {-L_}, {dx}, {"re_u", "im_u"}, true};
}

RCP<const RowEvaluator> Nls1d::rowKernel(const std::vector<double>& mu) const {
  GPHR_REQUIRE(mu.size() == box_.names.size(), InputError, name(), " takes ", box_.names.size(), " parameter(s), got ",
               mu.size());
  return makeRowEvaluator(NlsKernel{mu[0]}, 4, 2);  // stencil (q_i, p_i)
}

std::pair<RCP<HamiltonianSystem>, RCP<Vector>> Nls1d::build(const RCP<const Comm>& comm,
                                                           const std::vector<double>& mu) const {
  return assemble(nullptr, comm, mu);
}

std::pair<RCP<HamiltonianSystem>, RCP<Vector>> Nls1d::rebuild(const HamiltonianSystem& like,
                                                             const std::vector<double>& mu) const {
  GPHR_REQUIRE(like.space().n() == n_ && like.nonlinearTerm().maxStencilSize() == 2, InputError,
               "nls1d: a system of n = ", like.space().n(), " and stencils of ", like.nonlinearTerm().maxStencilSize(),
               " entries cannot lend its layout to this scene (n = ", n_, ", stencils of 2)");
  return assemble(&like, like.space().comm(), mu);
}

std::pair<RCP<HamiltonianSystem>, RCP<Vector>> Nls1d::assemble(const HamiltonianSystem* like,
                                                              const RCP<const Comm>& comm,
                                                              const std::vector<double>& mu) const {
  GPHR_REQUIRE(mu.size() == box_.names.size(), InputError, name(), " takes ", box_.names.size(), " parameter(s), got ",
               mu.size());
  const double eps = mu[0], dx = 2 * L_ / n_, c = 1.0 / (dx * dx);
  const double a = pulse_ ? mu[1] : 1.0, velocity = pulse_ ? mu[2] : 0.5;  // the pulse (paper: 1, 1/2)
  const RCP<const PhaseSpace> space = like ? like->spacePtr() : rcp<const PhaseSpace>(new PhaseSpace(n_, comm));
  const auto& map = space->map();
  // L = blockdiag(-Dxx, -Dxx), periodic second-order central differences; on like's graph the
  // values replace the zeros of a matrix on that (static) graph.
  auto L = like ? rcp(new CrsMatrix(like->linearPart().getCrsGraph())) : rcp(new CrsMatrix(map, 3));
  auto y0 = rcp(new Vector(map));
  Stencil st;
  {
    auto yv = y0->getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (LO il = 0; il < space->numLocalDofs(); ++il) {
      const GO i = space->firstLocalDof() + il;
      const GO im = (i + n_ - 1) % n_, ip = (i + 1) % n_;
      for (GO off : {GO(0), n_}) {
        const auto cols = Teuchos::tuple<GO>(off + im, off + i, off + ip);
        const auto vals = Teuchos::tuple<Scalar>(-c, 2 * c, -c);
        if (like) L->replaceGlobalValues(off + i, cols, vals);
        else L->insertGlobalValues(off + i, cols, vals);
      }
      const double x = -L_ + i * dx, amp = a * std::sqrt(2.0) / std::cosh(x);
      yv(il, 0) = amp * std::cos(velocity * x);
      yv(space->numLocalDofs() + il, 0) = amp * std::sin(velocity * x);
      if (like) continue;
      st.gids.push_back(i);
      st.gids.push_back(n_ + i);
      st.offsets.push_back(st.gids.size());
    }
  }
  L->fillComplete(map, map);
  RCP<const NonlinearTerm> term;
  if (like) {
    term = makeRowKernelTerm(NlsKernel{eps}, like->nonlinearTerm(), 4);
  } else {
    auto v = rcp(new Vector(space->dofMap()));
    v->putScalar(1.0);
    term = makeRowKernelTerm(NlsKernel{eps}, space->dofMap(), map, std::move(st), v, 4);
  }
  auto system = rcp(new HamiltonianSystem(space, L, rcp(new Vector(map)), 0.0, term));
  return {system, y0};
}

}  // namespace gphr
