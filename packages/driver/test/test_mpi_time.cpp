// The PMPI interposer that the gphr executable links (MpiTimeInterposer.cpp, gphr_time_mpi in
// cmake/GPHRPackage.cmake), linked here the same way:
//  - it registers itself: mpiTimeAvailable();
//  - calls made by a shared library (Teuchos' MpiComm in libteuchoscomm.so, as Tpetra and HDF5
//    make theirs) reach it: the executable exports its MPI_* symbols;
//  - each MPI function is a kind of its own: the kinds' calls add up to the total exactly, their
//    wall seconds to the total's up to the conversion from nanoseconds, and a barrier is counted
//    as MPI_Barrier;
//  - on 2 ranks, a rank that waits in a barrier for a sleeping one has that wait counted as time
//    inside MPI (and as MPI_Barrier's), and its compute seconds (CPU outside MPI) stay near zero
//    although it spun;
//  - with the critical path switched on, a collective lifts every rank's counter to the slowest
//    rank's: a rank that waited has the working rank's seconds as its share, not its own ~0.
#include <gtest/gtest.h>

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_DefaultComm.hpp>

#include <chrono>
#include <cstring>
#include <ctime>
#include <thread>

#include "gphr/core/StageClock.hpp"

using namespace gphr;

namespace {
// The interposer's kind of MPI function `name`, or -1.
int kindOf(const char* name) {
  for (int k = 0; k < kMpiCallKinds; ++k)
    if (mpiCallName(k) && std::strcmp(mpiCallName(k), name) == 0) return k;
  return -1;
}
}  // namespace

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
  // Exactly one MPI_Barrier; the allreduce is MPI_Allreduce (Teuchos might add calls of its own).
  const int barrier = kindOf("MPI_Barrier"), allreduce = kindOf("MPI_Allreduce");
  ASSERT_GE(barrier, 0);
  ASSERT_GE(allreduce, 0);
  EXPECT_EQ(after.callCount[barrier] - before.callCount[barrier], 1);
  EXPECT_GE(after.callCount[allreduce] - before.callCount[allreduce], 1);
  // The kinds split the totals: the same nanosecond differences are added to both, so the calls
  // agree exactly and the seconds to the conversion of each sum (kMpiCallKinds + 1 roundings of
  // at most 1e-16 relative each on totals of seconds: 1e-12 s is far above it and far below a call).
  long long calls = 0;
  double wall = 0.0;
  for (int k = 0; k < kMpiCallKinds; ++k) {
    calls += after.callCount[k];
    wall += after.callWall[k];
    if (!mpiCallName(k)) {
      EXPECT_EQ(after.callCount[k], 0) << "kind " << k << " has no name but calls";
    }
  }
  EXPECT_EQ(calls, after.calls);
  EXPECT_NEAR(wall, after.wall, 1e-12 + 1e-14 * after.wall);
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
    // ... and it is the barrier's: the stage's one MPI_Barrier holds all but the clock reads'
    // microseconds (no other MPI call is made inside the stage).
    const int barrier = kindOf("MPI_Barrier");
    ASSERT_GE(barrier, 0);
    EXPECT_EQ(w.callCount[barrier], 1);
    EXPECT_NEAR(w.callWall[barrier], w.mpiWall, 1e-9);
    // Outside MPI rank 0 only reads clocks: microseconds. 0.02 s leaves room for Open MPI's own
    // threads, which CLOCK_PROCESS_CPUTIME_ID counts; a wait not subtracted (Open MPI polls while
    // it waits) would show a large part of the 0.3 s here.
    EXPECT_LT(w.compute(), 0.02);
  }
}

namespace {
// Spends `seconds` of this thread's CPU outside MPI.
void burnCpu(double seconds) {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  const double start = static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
  volatile double x = 1.0;
  for (double now = start; now - start < seconds;) {
    for (int i = 0; i < 10000; ++i) x = x * 1.0000001 + 1e-9;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    now = static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
  }
}
}  // namespace

TEST(MpiTime, CriticalPathWaitsForTheSlowestRankAtACollective) {
  const auto comm = Teuchos::DefaultComm<int>::getComm();
  const double work = 0.25;
  // Off (the default): nothing is kept.
  ASSERT_FALSE(criticalPathMeasured()) << "run without GPHR_CRITICAL_PATH=1 in the environment";
  EXPECT_EQ(mpiTimeNow().critical, 0.0);
  // On, on every rank before the same collective (the switch must agree at each one).
  setCriticalPathMeasured(true);
  Teuchos::barrier(*comm);
  StageClocks c;
  {
    const StageClocks::Scope s(c, "work");
    if (comm->getRank() == comm->getSize() - 1) burnCpu(work);  // the last rank works, the others wait
    Teuchos::barrier(*comm);
  }
  setCriticalPathMeasured(false);
  Teuchos::barrier(*comm);
  const StageTime& w = c.stages().at(0);
  // Every rank's share of the critical path is the working rank's `work` seconds: the barrier
  // lifted the waiting ranks' counters to it although their own compute is near zero (without the
  // agreement rank 0 of 2 would read ~0). Upper bound: the burn overshoots by one inner loop
  // (microseconds), and the clock reads and the barrier's bookkeeping add microseconds; 0.05 s
  // leaves room for a scheduler slice, which CLOCK_THREAD_CPUTIME_ID does not count anyway.
  // Lower bound: the working rank's burn, less the waiting rank's own microseconds between the
  // first barrier and the stage's start (read at its start, not added by the working rank).
  EXPECT_GE(w.critical, work - 0.005);
  EXPECT_LE(w.critical, work + 0.05);
  if (comm->getRank() != comm->getSize() - 1) {
    EXPECT_LT(w.compute(), 0.02);  // the waiting rank's own work: clock reads (as in the test above)
  }
}
