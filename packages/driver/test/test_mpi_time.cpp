// The PMPI interposer that the gphr executable links (MpiTimeInterposer.cpp, gphr_time_mpi in
// cmake/GPHRPackage.cmake), linked here the same way:
//  - it registers itself: mpiTimeAvailable();
//  - calls made by a shared library (Teuchos' MpiComm in libteuchoscomm.so, as Tpetra and HDF5
//    make theirs) reach it: the executable exports its MPI_* symbols;
//  - on 2 ranks, a rank that waits in a barrier for a sleeping one has that wait counted as time
//    inside MPI, and its compute seconds (CPU outside MPI) stay near zero although it spun.
#include <gtest/gtest.h>

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_DefaultComm.hpp>

#include <chrono>
#include <thread>

#include "gphr/core/StageClock.hpp"

using namespace gphr;

TEST(MpiTime, InterposerRegistersAndCountsCallsFromSharedLibraries) {
  ASSERT_TRUE(mpiTimeAvailable());
  const auto comm = Teuchos::DefaultComm<int>::getComm();
  const MpiTime before = mpiTimeNow();
  Teuchos::barrier(*comm);
  int one = 1, sum = 0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, one, Teuchos::outArg(sum));
  const MpiTime after = mpiTimeNow();
  EXPECT_EQ(sum, comm->getSize());
  // Teuchos makes one MPI call for each (MPI_Barrier, MPI_Allreduce), even on one rank.
  EXPECT_GE(after.calls - before.calls, 2);
  EXPECT_GE(after.wall, before.wall);
  EXPECT_GE(after.cpu, before.cpu);
}

TEST(MpiTime, WaitInMpiIsNotCompute) {
  const auto comm = Teuchos::DefaultComm<int>::getComm();
  if (comm->getSize() < 2) GTEST_SKIP() << "needs a rank to wait for";
  const double sleep = 0.3;
  Teuchos::barrier(*comm);  // the ranks leave together (up to scheduling skew)
  StageClocks c;
  {
    const StageClocks::Scope s(c, "wait");
    if (comm->getRank() == 1) std::this_thread::sleep_for(std::chrono::duration<double>(sleep));
    Teuchos::barrier(*comm);
  }
  const StageTime& w = c.stages().at(0);
  if (comm->getRank() == 0) {
    // Rank 0 waits about `sleep` inside the barrier; the skew with which the ranks left the first
    // barrier (oversubscribed in ctest: at most a scheduler slice or two, well under 0.1 s) is
    // the only thing that shortens it.
    EXPECT_GE(w.mpiWall, sleep - 0.1);
    EXPECT_LE(w.mpiWall, w.wall);
    // Outside MPI rank 0 only reads clocks: microseconds. 0.02 s leaves room for Open MPI's own
    // threads, which CLOCK_PROCESS_CPUTIME_ID counts; a wait not subtracted (Open MPI polls while
    // it waits) would show a large part of the 0.3 s here.
    EXPECT_LT(w.compute(), 0.02);
  }
}
