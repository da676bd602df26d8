// The same full-model run on P ranks (P = 2, 3 in CTest) agrees with a serial run to 1e-12
// relative. The serial reference runs in the same process on a one-rank sub-communicator, so
// the comparison needs no files. On one rank both runs would be the same run: the tests skip. Differences come from summation order (round-off) and from the
// block-Jacobi preconditioner changing with P, which only moves where Newton stops: with a
// Newton tolerance of 1e-13 (absolute, states of norm ~10) the runs agree to ~1e-14.
#include <gtest/gtest.h>
#include <mpi.h>

#include <Teuchos_DefaultMpiComm.hpp>

#include "TestUtils.hpp"
#include "gphr/models/Scene.hpp"
#include "gphr/timeint/FullModelIntegrator.hpp"

using namespace gphr;

namespace {

RCP<const Comm> serialComm() {
  MPI_Comm sub;
  const int rank = test::comm()->getRank();
  MPI_Comm_split(MPI_COMM_WORLD, rank == 0 ? 0 : MPI_UNDEFINED, 0, &sub);
  if (rank != 0) return Teuchos::null;
  return rcp(new Teuchos::MpiComm<int>(Teuchos::opaqueWrapper(sub, MPI_Comm_free)));
}

// Final state of `steps` steps, gathered to rank 0 in global-id order (empty elsewhere).
std::vector<double> finalState(const Scene& scene, const std::vector<double>& mu, const std::string& scheme,
                               const RCP<const Comm>& comm, long steps, double dt) {
  auto s = scene.instantiate(comm, mu, true);
  Teuchos::ParameterList pl("integrator");
  pl.set("scheme", scheme);
  pl.set("newtonTolerance", 1e-13);
  pl.sublist("linearSolver").set("tolerance", 1e-14);
  FullModelIntegrator integ(s.system, pl);
  Vector y(*s.y0, Teuchos::Copy);
  integ.run(y, dt, steps);
  const GO N = s.system->space().fullDim();
  auto root = rcp(new Map(N, comm->getRank() == 0 ? N : 0, 0, comm));
  Vector all(root);
  all.doImport(y, Import(y.getMap(), root), Tpetra::INSERT);
  auto d = all.getData();
  return std::vector<double>(d.begin(), d.end());
}

void compare(const Scene& scene, const std::vector<double>& mu, double dt) {
  if (test::comm()->getSize() == 1) GTEST_SKIP() << "compares P > 1 ranks with one; run with mpirun -np 2 or 3";
  auto serial = serialComm();
  for (const char* scheme : {"imr", "avf"}) {
    auto dist = finalState(scene, mu, scheme, test::comm(), 60, dt);
    if (serial.is_null()) continue;
    auto ref = finalState(scene, mu, scheme, serial, 60, dt);
    ASSERT_EQ(dist.size(), ref.size());
    double diff = 0.0, nrm = 0.0;
    for (size_t i = 0; i < ref.size(); ++i) {
      diff += (dist[i] - ref[i]) * (dist[i] - ref[i]);
      nrm += ref[i] * ref[i];
    }
    EXPECT_LE(std::sqrt(diff), 1e-12 * std::sqrt(nrm)) << scene.name() << " " << scheme;
    EXPECT_GT(nrm, 0.0);
  }
}

TEST(RankAgreement, NlsFullModel) { compare(Nls1d(96), {1.0932}, 0.01); }
TEST(RankAgreement, SweFullModel) { compare(Swe2d(10), {1.6435, 0.7762}, 0.005); }

}  // namespace
