#pragma once
/// @file
/// The training states of the hyper-reduction stages in reduced coordinates (paper eq:snaps_JG,
/// shifted as in Sec. 3.3): for every N-th stored state y_s of each training system j, z = A^T y_s
/// and the row kernel of G at y0_j + A z on this rank's own rows of G. Both offline rules that
/// choose terms read their snapshots here: the DEIM basis (rows of J_G A, eq:snaps_JG) and the
/// empirical quadrature (the same rows, read as each term's reduced gradient, and G_e - G_e(y0)).
#include <algorithm>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "gphr/core/Error.hpp"
#include "gphr/core/SnapshotSet.hpp"
#include "gphr/core/SystemSet.hpp"
#include "gphr/core/HamiltonianSystem.hpp"
#include "gphr/reduction/ReducedRowKernel.hpp"

namespace gphr {

/// The used snapshots s in [first, last) (numbered over all systems in order, every N-th state of
/// each block: see forEachJacobianSnapshot).
struct SnapshotRange {
  long first = 0;                                   ///< the first used snapshot
  long last = std::numeric_limits<long>::max();     ///< past the last one
};

/// The reduced states z = A^T y of the block read last (2k x its states): visits of the same block
/// one after another (the hierarchical POD's chunks cut the blocks) then read it once, and nothing
/// of the block's size stays alive between them.
struct ReducedStateCache {
  size_t block = static_cast<size_t>(-1);  ///< the block Z belongs to
  RCP<MultiVector> Z;                      ///< A^T y for its used states (every every-th)
};

/// The number of snapshots forEachJacobianSnapshot visits: ceil(columns_j / every) summed over the blocks.
inline long usedSnapshotCount(const SnapshotSet& states, int every) {
  long used = 0;
  for (size_t j = 0; j < states.size(); ++j) used += (static_cast<long>(states.numColumns(j)) + every - 1) / every;
  return used;
}

/// Calls fn(jac, index) -- or fn(jac, index, kernel), when fn takes the evaluated kernel too -- for
/// every used snapshot in `range`, jac = this rank's rows of J_G(y0_j + A A^T y_s) A (row-major,
/// local rows x 2k); a block with none of the range's snapshots is not read. Returns the number of
/// snapshots visited. With `cache`, a block's reduced states are kept there for the next call.
/// Collective.
template <class Fn>
long forEachJacobianSnapshotIn(const SystemSet& systems,
                               const SnapshotSet& states, const MultiVector& A, int every, SnapshotRange range,
                               std::vector<Scalar>& jac, Fn&& fn, ReducedStateCache* cache = nullptr) {
  const RCP<const Map> rowMap = systems[0]->nonlinearTerm().rowMap();
  const int r = static_cast<int>(A.getNumVectors());
  auto local = rcp(new Map(r, 0, rowMap->getComm(), Tpetra::LocallyReplicated));
  long index = 0, visited = 0;  // index: the used snapshot's number over all blocks
  for (size_t j = 0; j < systems.size(); ++j) {
    const long inBlock = (static_cast<long>(states.numColumns(j)) + every - 1) / every;
    if (index + inBlock <= range.first || index >= range.last) {
      index += inBlock;
      continue;
    }
    const HamiltonianSystem& sys = *systems[j];
    GPHR_REQUIRE(sys.nonlinearTerm().rowMap()->isSameAs(*rowMap), InputError, "training system ", j,
                 " has another row map of G");
    ReducedRowKernel kernel(sys.nonlinearTermPtr(), ownedRowSample(sys, A), sys.space().comm());
    ReducedStateCache own;
    ReducedStateCache& zc = cache ? *cache : own;
    if (zc.block != j || zc.Z.is_null()) {  // z = A^T y_s of the used states only, read in column blocks
      zc.Z = rcp(new MultiVector(local, static_cast<size_t>(inBlock)));
      for (size_t u0 = 0; u0 < static_cast<size_t>(inBlock); u0 += kSnapshotReadColumns) {
        const size_t n = std::min(kSnapshotReadColumns, static_cast<size_t>(inBlock) - u0);
        const RCP<const MultiVector> Y = states.columns(j, static_cast<size_t>(every), u0, n);
        zc.Z->subViewNonConst(Teuchos::Range1D(u0, u0 + n - 1))
            ->multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, A, *Y, 0.0);
      }
      zc.block = j;
    }
    auto zv = zc.Z->getLocalViewHost(Tpetra::Access::ReadOnly);
    Teuchos::SerialDenseVector<int, double> z(r);
    for (long u = 0; u < inBlock; ++u, ++index) {
      if (index < range.first || index >= range.last) continue;
      for (int i = 0; i < r; ++i) z(i) = zv(i, u);
      kernel.evaluate(z, true, false);
      kernel.reducedJacobian(jac.data());
      if constexpr (std::is_invocable_v<Fn, std::vector<Scalar>&, long, ReducedRowKernel&>)
        fn(jac, index, kernel);
      else
        fn(jac, index);
      ++visited;
    }
  }
  return visited;
}

/// Calls fn(jac, index) -- or fn(jac, index, kernel), when fn takes the evaluated kernel too -- for
/// every used snapshot, jac = this rank's rows of J_G(y0_j + A A^T y_s) A (row-major, local rows x
/// 2k). Returns the number of snapshots used. Collective.
template <class Fn>
long forEachJacobianSnapshot(const SystemSet& systems,
                             const SnapshotSet& states, const MultiVector& A, int every,
                             std::vector<Scalar>& jac, Fn&& fn) {
  return forEachJacobianSnapshotIn(systems, states, A, every, SnapshotRange{}, jac, std::forward<Fn>(fn));
}

}  // namespace gphr
