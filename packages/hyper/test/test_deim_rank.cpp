// The DEIM basis' numerical rank (kDeimRankFloor) on a case whose rank is known exactly: SWE
// 20 x 20, 3 x 3 training parameters, every 10th state, 2k = 20 (the case where the former floor of
// n_cols eps kept 79 vectors on one OpenBLAS thread and 80 on two). Its snapshot matrix, formed
// whole and factored by one LAPACK SVD (independent of the streaming POD), has a gap of many
// orders after its rank: the streaming POD -- in one chunk or in several with a root, in many
// small steps or few large ones -- must keep exactly that many vectors on any rank count, any
// OpenBLAS kernel and thread count (scripts/portability.sh runs this test under each).
#include <gtest/gtest.h>

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_LAPACK.hpp>

#include "HyperTestUtils.hpp"
#include "gphr/hyper/JacobianSnapshots.hpp"

using namespace gphr;
using namespace gphr::test;

namespace {

constexpr int kEvery = 10;

struct SweRankCase {
  std::vector<RCP<const HamiltonianSystem>> systems;
  std::vector<RCP<const MultiVector>> states;
  RCP<const MultiVector> A;
};

SweRankCase sweCase() {
  Swe2d scene(20);
  SweRankCase c;
  for (double beta : {1.1, 1.4, 1.7})
    for (double gamma : {0.7, 1.0, 1.3}) {
      auto inst = scene.instantiate(comm(), {beta, gamma}, true);
      c.states.push_back(fomSnapshots(inst, "imr", 0.01, 200));
      c.systems.push_back(inst.system);
    }
  BasisOptions opt;
  opt.k = 10;
  c.A = computeSymplecticBasis(c.states, c.systems[0]->space(), opt).A;
  return c;
}

// The singular values of the whole snapshot matrix [J_1 A, J_2 A, ...] (d x 2k snapshots), by
// one LAPACK GESVD on rank 0 (broadcast): the reference the streaming POD is held to.
std::vector<double> referenceSingularValues(const SweRankCase& c) {
  const RCP<const Map> rows = c.systems[0]->nonlinearTerm().rowMap();
  const int r = static_cast<int>(c.A->getNumVectors());
  const LO nl = static_cast<LO>(rows->getNodeNumElements());
  std::vector<std::vector<Scalar>> columns;
  std::vector<Scalar> jac(static_cast<size_t>(nl) * r);  // filled per snapshot, as the POD's
  forEachJacobianSnapshot(c.systems, c.states, *c.A, kEvery, jac, [&](const auto& J, long) {
    for (int a = 0; a < r; ++a) {
      std::vector<Scalar> col(nl);
      for (LO i = 0; i < nl; ++i) col[i] = J[static_cast<size_t>(i) * r + a];
      columns.push_back(col);
    }
  });
  MultiVector M(rows, columns.size());
  {
    auto m = M.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (size_t j = 0; j < columns.size(); ++j)
      for (LO i = 0; i < nl; ++i) m(i, j) = columns[j][i];
  }
  std::vector<double> all = gatherColumns(M);  // rank 0: column-major d x cols
  const int d = static_cast<int>(rows->getGlobalNumElements()), cols = static_cast<int>(columns.size());
  std::vector<double> sigma(std::min(d, cols), 0.0);
  if (comm()->getRank() == 0) {
    Teuchos::LAPACK<int, double> lapack;
    std::vector<double> work(1);
    int info = 0;
    lapack.GESVD('N', 'N', d, cols, all.data(), d, sigma.data(), nullptr, 1, nullptr, 1, work.data(), -1, nullptr, &info);
    work.resize(static_cast<size_t>(work[0]));
    lapack.GESVD('N', 'N', d, cols, all.data(), d, sigma.data(), nullptr, 1, nullptr, 1, work.data(),
                 static_cast<int>(work.size()), nullptr, &info);
    EXPECT_EQ(info, 0);
  }
  Teuchos::broadcast(*comm(), 0, static_cast<int>(sigma.size()), sigma.data());
  return sigma;
}

}  // namespace

TEST(DeimBasisRank, IsTheSnapshotsRankAboveRoundOffOnAnyRouteAndRankCount) {
  const SweRankCase c = sweCase();
  const std::vector<double> sigma = referenceSingularValues(c);
  int rank = 0;
  while (rank < static_cast<int>(sigma.size()) && sigma[rank] > kDeimRankFloor * sigma[0]) ++rank;
  ASSERT_GT(rank, 0);
  ASSERT_LT(rank, static_cast<int>(sigma.size()));
  // The rank is known exactly: the last kept value is far above the floor and the first dropped
  // one at round-off (4e-14 .. 1e-13 of sigma_1 on 1-3 ranks: the training trajectories differ at
  // round-off with the ranks), so no floor in between can change the count; the floor (1e-12)
  // must sit above it: 5e-13 leaves it a margin of 2.
  std::printf("reference SVD: rank %d of %zu, sigma_r / sigma_1 = %.2e, sigma_r+1 / sigma_1 = %.2e\n", rank,
              sigma.size(), sigma[rank - 1] / sigma[0], sigma[rank] / sigma[0]);
  EXPECT_GT(sigma[rank - 1], 1e-8 * sigma[0]);
  EXPECT_LT(sigma[rank], 0.5 * kDeimRankFloor * sigma[0]);
  struct Route {
    const char* name;
    int blockSnapshots, chunkSnapshots;
  };
  for (const Route& route : {Route{"one chunk, default steps", 0, 0}, Route{"one chunk, 2 snapshots a step", 2, 0},
                             Route{"4 chunks and a root", 0, 48}, Route{"2 chunks and a root", 3, 100}}) {
    DeimBasisOptions opt;
    opt.snapshotEvery = kEvery;
    opt.maxRank = 112;  // gphr's default for m up to 80, max(m) + 32: truncated between steps
    opt.blockSnapshots = route.blockSnapshots;
    opt.chunkSnapshots = route.chunkSnapshots;
    const DeimBasis deim = computeDeimBasis(c.systems, c.states, *c.A, opt);
    EXPECT_EQ(static_cast<int>(deim.U->getNumVectors()), rank) << route.name;
    EXPECT_LT(orthonormalityError(*deim.U), 1e-12) << route.name;
  }
}
