// GPHR's gtest main: Tpetra::ScopeGuard (MPI + Kokkos), then RUN_ALL_TESTS, then a reduction of
// the result over ranks so that a failure on any rank fails the test on all (PLATFORM.md).
#include <gtest/gtest.h>
#include <mpi.h>

#include <cstdlib>
#include <string>

#include <Tpetra_Core.hpp>

int main(int argc, char** argv) {
  Tpetra::ScopeGuard scope(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  // One rank prints; all run. GPHR_TEST_ALL_RANKS=1 in the environment: every rank prints (a
  // failure only some rank sees is otherwise told by the exit code alone).
  const char* all = std::getenv("GPHR_TEST_ALL_RANKS");
  if (rank != 0 && !(all && std::string(all) == "1")) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  int local = RUN_ALL_TESTS(), global = 0;
  MPI_Allreduce(&local, &global, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return global;
}
