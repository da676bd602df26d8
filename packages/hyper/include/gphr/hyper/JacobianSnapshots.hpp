#pragma once
/// @file
/// The training states of the hyper-reduction stages in reduced coordinates (paper eq:snaps_JG,
/// shifted as in Sec. 3.3): for every N-th stored state y_s of each training system j, z = A^T y_s
/// and the row kernel of G at y0_j + A z on this rank's own rows of G. Both offline rules that
/// choose terms read their snapshots here: the DEIM basis (rows of J_G A, eq:snaps_JG) and the
/// empirical quadrature (the same rows, read as each term's reduced gradient, and G_e - G_e(y0)).
#include <type_traits>
#include <vector>

#include "gphr/core/Error.hpp"
#include "gphr/core/SnapshotSet.hpp"
#include "gphr/core/HamiltonianSystem.hpp"
#include "gphr/reduction/ReducedRowKernel.hpp"

namespace gphr {

/// Calls fn(jac, index) -- or fn(jac, index, kernel), when fn takes the evaluated kernel too -- for
/// every used snapshot, jac = this rank's rows of J_G(y0_j + A A^T y_s) A (row-major, local rows x
/// 2k). Returns the number of snapshots used. Collective.
template <class Fn>
long forEachJacobianSnapshot(const std::vector<RCP<const HamiltonianSystem>>& systems,
                             const SnapshotSet& states, const MultiVector& A, int every,
                             std::vector<Scalar>& jac, Fn&& fn) {
  const RCP<const Map> rowMap = systems[0]->nonlinearTerm().rowMap();
  const int r = static_cast<int>(A.getNumVectors());
  auto local = rcp(new Map(r, 0, rowMap->getComm(), Tpetra::LocallyReplicated));
  long used = 0;
  for (size_t j = 0; j < systems.size(); ++j) {
    const HamiltonianSystem& sys = *systems[j];
    GPHR_REQUIRE(sys.nonlinearTerm().rowMap()->isSameAs(*rowMap), InputError, "training system ", j,
                 " has another row map of G");
    ReducedRowKernel kernel(sys.nonlinearTermPtr(), ownedRowSample(sys, A), sys.space().comm());
    MultiVector Z(local, states.numColumns(j));
    Z.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, A, *states[j], 0.0);  // z = A^T y_s (the block read once)
    auto zv = Z.getLocalViewHost(Tpetra::Access::ReadOnly);
    Teuchos::SerialDenseVector<int, double> z(r);
    for (size_t c = 0; c < states.numColumns(j); c += every) {
      for (int i = 0; i < r; ++i) z(i) = zv(i, c);
      kernel.evaluate(z, true, false);
      kernel.reducedJacobian(jac.data());
      if constexpr (std::is_invocable_v<Fn, std::vector<Scalar>&, long, ReducedRowKernel&>)
        fn(jac, used++, kernel);
      else
        fn(jac, used++);
    }
  }
  return used;
}

}  // namespace gphr
