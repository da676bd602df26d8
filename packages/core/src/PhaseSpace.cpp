#include "gphr/core/PhaseSpace.hpp"

#include "gphr/core/Error.hpp"

namespace gphr {

PhaseSpace::PhaseSpace(GO n, const RCP<const Comm>& comm) : n_(n) {
  GPHR_REQUIRE(n >= 1, InputError, "phase space size n = ", n, " is not allowed: n must be >= 1");
  dofMap_ = rcp(new Map(static_cast<Tpetra::global_size_t>(n), 0, comm));
  nLocal_ = static_cast<LO>(dofMap_->getNodeNumElements());
  first_ = nLocal_ > 0 ? dofMap_->getMinGlobalIndex() : 0;
  std::vector<GO> gids(2 * static_cast<size_t>(nLocal_));
  for (LO i = 0; i < nLocal_; ++i) {
    gids[i] = first_ + i;
    gids[nLocal_ + i] = n + first_ + i;
  }
  map_ = rcp(new Map(static_cast<Tpetra::global_size_t>(2 * n),
                     Teuchos::ArrayView<const GO>(gids.data(), gids.size()), 0, comm));
}

namespace {
// out_q = sign * x_p, out_p = -sign * x_q, locally (see the layout comment in the header).
void applyCanonical(const MultiVector& x, MultiVector& out, LO nLocal, double sign) {
  auto xv = x.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto ov = out.getLocalViewHost(Tpetra::Access::OverwriteAll);
  const LO nc = static_cast<LO>(x.getNumVectors());
  Kokkos::parallel_for(
      "gphr::applyJ", Kokkos::RangePolicy<ExecSpace>(0, nLocal), KOKKOS_LAMBDA(const LO i) {
        for (LO c = 0; c < nc; ++c) {
          ov(i, c) = sign * xv(nLocal + i, c);
          ov(nLocal + i, c) = -sign * xv(i, c);
        }
      });
}
}  // namespace

void PhaseSpace::applyJ(const MultiVector& x, MultiVector& out) const {
  applyCanonical(x, out, nLocal_, 1.0);
}
void PhaseSpace::applyJT(const MultiVector& x, MultiVector& out) const {
  applyCanonical(x, out, nLocal_, -1.0);
}

}  // namespace gphr
