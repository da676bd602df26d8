#include "gphr/hyper/DeimBasis.hpp"

#include "gphr/core/Error.hpp"
#include "gphr/reduction/ReducedRowKernel.hpp"
#include "gphr/reduction/StreamingPod.hpp"

namespace gphr {

DeimBasis computeDeimBasis(const std::vector<RCP<const HamiltonianSystem>>& systems,
                           const std::vector<RCP<const MultiVector>>& states, const MultiVector& A,
                           const DeimBasisOptions& opt) {
  GPHR_REQUIRE(!systems.empty() && systems.size() == states.size(), InputError, "DEIM basis: ", systems.size(),
               " systems for ", states.size(), " snapshot sets (need one per training parameter)");
  GPHR_REQUIRE(opt.snapshotEvery >= 1, InputError, "DEIM basis: snapshotEvery = ", opt.snapshotEvery,
               " (allowed: >= 1)");
  const RCP<const Map> rowMap = systems[0]->nonlinearTerm().rowMap();
  const int r = static_cast<int>(A.getNumVectors());
  const LO nl = static_cast<LO>(rowMap->getNodeNumElements());
  const GO d = static_cast<GO>(rowMap->getGlobalNumElements());
  const int maxRank = static_cast<int>(std::min<GO>(d, opt.maxRank > 0 ? opt.maxRank : kDefaultDeimRank));
  // Snapshots per POD step (the same on any rank count): a step costs O(d (rank + columns)^2), so
  // about maxRank new columns per step balances the number of steps against their size.
  const int perBlock = opt.blockSnapshots > 0 ? opt.blockSnapshots : std::max(1, (maxRank + r - 1) / r);
  StreamingPod pod(rowMap, maxRank, perBlock * r);
  auto local = rcp(new Map(r, 0, rowMap->getComm(), Tpetra::LocallyReplicated));
  MultiVector block(rowMap, static_cast<size_t>(perBlock) * r);
  std::vector<Scalar> jac(static_cast<size_t>(nl) * r);
  int filled = 0;
  long used = 0;
  auto flush = [&] {
    if (filled == 0) return;
    if (filled == perBlock) {
      pod.add(block);
    } else {
      pod.add(*block.subView(Teuchos::Range1D(0, static_cast<size_t>(filled) * r - 1)));
    }
    filled = 0;
  };
  for (size_t j = 0; j < systems.size(); ++j) {
    const HamiltonianSystem& sys = *systems[j];
    GPHR_REQUIRE(sys.nonlinearTerm().rowMap()->isSameAs(*rowMap), InputError,
                 "DEIM basis: training system ", j, " has another row map of G");
    ReducedRowKernel kernel(sys.nonlinearTermPtr(), ownedRowSample(sys, A), sys.space().comm());
    MultiVector Z(local, states[j]->getNumVectors());
    Z.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, A, *states[j], 0.0);  // z = A^T y_s
    auto zv = Z.getLocalViewHost(Tpetra::Access::ReadOnly);
    Teuchos::SerialDenseVector<int, double> z(r);
    for (size_t c = 0; c < states[j]->getNumVectors(); c += opt.snapshotEvery) {
      for (int i = 0; i < r; ++i) z(i) = zv(i, c);
      kernel.evaluate(z, true, false);
      kernel.reducedJacobian(jac.data());
      {
        auto b = block.getLocalViewHost(Tpetra::Access::ReadWrite);
        for (LO i = 0; i < nl; ++i)
          for (int a = 0; a < r; ++a) b(i, static_cast<size_t>(filled) * r + a) = jac[static_cast<size_t>(i) * r + a];
      }
      ++used;
      if (++filled == perBlock) flush();
    }
  }
  flush();
  DeimBasis out;
  out.singularValues = pod.singularValues();
  out.snapshots = used;
  out.energy = pod.totalEnergy();
  GPHR_REQUIRE(pod.rank() > 0, InputError, "DEIM basis: the ", used,
               " reduced-Jacobian snapshots are all zero (a linear problem, e.g. eps = 0, has nothing to hyper-reduce)");
  out.U = rcp(new MultiVector(pod.leftVectors(), Teuchos::Copy));
  return out;
}

}  // namespace gphr
