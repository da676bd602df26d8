// The PMPI interposer of the `gphr` executable (doc/scaling.md, "Per-stage clocks"): every MPI
// call that can wait or move data (collectives, point-to-point, waits and tests, communicator
// creation, MPI-IO) is defined here, times its PMPI_ twin and adds the time to per-process
// counters that gphr::StageClocks reads through setMpiTimeSource(). The list is what `nm -D
// --undefined-only` shows the executable and its libraries (Trilinos, parallel HDF5, GPHR) call
// among those that can block; calls that only describe (types, groups, attributes) stay
// untimed. The executable exports these symbols (-Wl,--export-dynamic-symbol=MPI_*, see
// packages/driver/CMakeLists.txt), so the shared libraries' calls resolve here too.
//
// Each wrapped function is a kind of its own (StageClock.hpp, MpiTime::callWall): its wall
// nanoseconds and calls are added beside the totals, from the same clock readings, so that the
// kinds add up to the totals; gphr build writes them per stage as DIR/mpi_calls.csv.
//
// Only the outermost call of a thread is counted (an MPI call made inside another, as MPI-IO
// does, is not counted twice). CPU seconds are the calling thread's (CLOCK_THREAD_CPUTIME_ID),
// so with several threads (gphr query --threads) the per-process sum is still the CPU spent
// inside MPI, and "compute = process CPU - MPI CPU" stays the CPU outside MPI.
//
// The compute critical path (MpiTime::critical; on with GPHR_CRITICAL_PATH=1, else not kept):
// each thread adds its CPU seconds between MPI calls to one counter, and every outermost
// collective call first makes the communicator's ranks agree on the largest counter (one extra
// 8-byte MPI_Allreduce, timed as the collective's own). A collective is taken as a point where
// every rank waits for the slowest; rooted ones (a broadcast's root does not wait) and
// point-to-point dependencies (a receive waiting for its sender's work) are not modelled, so the
// figure can only underestimate by the work a receive waited for between two collectives. Its
// use: on ranks that share cores (the 2-core VM running 16 ranks) the wall clock counts waiting
// for a core, and the critical path says what a node with a core per rank would wait for.
//
// Whole-process figures for commands without a stage table (gphr run, gphr query; bench/scaling.sh):
// with GPHR_PROCESS_CLOCKS=PREFIX in the environment, MPI_Finalize first writes PREFIX.RANK, one
// line in stages.csv's columns with the stage "process" (wall seconds since the executable's
// static initialisation, i.e. nearly since exec).
#define OMPI_SKIP_MPICXX 1  // the C API only: this file defines C functions
#include <mpi.h>

#include <sys/resource.h>
#include <time.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "gphr/core/StageClock.hpp"

namespace {

std::atomic<long long> g_wallNs{0}, g_cpuNs{0}, g_calls{0};
std::atomic<long long> g_kindNs[gphr::kMpiCallKinds], g_kindCalls[gphr::kMpiCallKinds];  // zero: static storage
const char* g_kindNames[gphr::kMpiCallKinds];  // filled by the GPHR_TIMED definitions' initialisers
std::atomic<long long> g_criticalNs{0};  // MpiTime::critical, nanoseconds
thread_local int t_depth = 0;
thread_local long long t_lastExitCpuNs = 0;  // the thread's CPU clock when it last left MPI

// Names kind `kind` (at static initialisation, one definition at a time); returns it.
int nameKind(int kind, const char* name) {
  g_kindNames[kind] = name;
  return kind;
}

long long nanoseconds(clockid_t clock) {
  timespec t{};
  clock_gettime(clock, &t);
  return static_cast<long long>(t.tv_sec) * 1000000000LL + t.tv_nsec;
}

gphr::MpiTime counters() {
  gphr::MpiTime t;
  t.wall = 1e-9 * static_cast<double>(g_wallNs.load(std::memory_order_relaxed));
  t.cpu = 1e-9 * static_cast<double>(g_cpuNs.load(std::memory_order_relaxed));
  t.calls = g_calls.load(std::memory_order_relaxed);
  for (int k = 0; k < gphr::kMpiCallKinds; ++k) {
    t.callWall[k] = 1e-9 * static_cast<double>(g_kindNs[k].load(std::memory_order_relaxed));
    t.callCount[k] = g_kindCalls[k].load(std::memory_order_relaxed);
  }
  if (gphr::criticalPathMeasured()) {  // with the calling thread's compute since it last left MPI
    const long long pending = t_depth == 0 ? nanoseconds(CLOCK_THREAD_CPUTIME_ID) - t_lastExitCpuNs : 0;
    t.critical = 1e-9 * static_cast<double>(g_criticalNs.load(std::memory_order_relaxed) + pending);
  }
  return t;
}

// The critical path at a collective call on `comm`: the largest counter among its ranks.
void agreeOnCriticalPath(MPI_Comm comm) {
  int inter = 0, size = 1;
  if (comm == MPI_COMM_NULL || PMPI_Comm_test_inter(comm, &inter) != MPI_SUCCESS || inter) return;
  if (PMPI_Comm_size(comm, &size) != MPI_SUCCESS || size < 2) return;
  long long ns = g_criticalNs.load(std::memory_order_relaxed);
  PMPI_Allreduce(MPI_IN_PLACE, &ns, 1, MPI_LONG_LONG, MPI_MAX, comm);
  g_criticalNs.store(ns, std::memory_order_relaxed);
}

// Times one MPI call of kind `kind`, if it is the thread's outermost; a collective one names its
// communicator, where the critical path is agreed on (see the top).
class TimedCall {
 public:
  explicit TimedCall(int kind, MPI_Comm collective = MPI_COMM_NULL) : kind_(kind), outer_(t_depth++ == 0) {
    if (!outer_) return;
    wall_ = nanoseconds(CLOCK_MONOTONIC), cpu_ = nanoseconds(CLOCK_THREAD_CPUTIME_ID);
    if (!gphr::criticalPathMeasured()) return;
    g_criticalNs.fetch_add(cpu_ - t_lastExitCpuNs, std::memory_order_relaxed);
    agreeOnCriticalPath(collective);
  }
  ~TimedCall() {
    --t_depth;
    if (!outer_) return;
    const long long wall = nanoseconds(CLOCK_MONOTONIC) - wall_;
    t_lastExitCpuNs = nanoseconds(CLOCK_THREAD_CPUTIME_ID);
    g_wallNs.fetch_add(wall, std::memory_order_relaxed);
    g_cpuNs.fetch_add(t_lastExitCpuNs - cpu_, std::memory_order_relaxed);
    g_calls.fetch_add(1, std::memory_order_relaxed);
    g_kindNs[kind_].fetch_add(wall, std::memory_order_relaxed);
    g_kindCalls[kind_].fetch_add(1, std::memory_order_relaxed);
  }
  TimedCall(const TimedCall&) = delete;
  TimedCall& operator=(const TimedCall&) = delete;

 private:
  int kind_;
  bool outer_;
  long long wall_ = 0, cpu_ = 0;
};

// Registers the counters and the kinds' names before main() runs (StageClock.cpp's registry is
// constant-initialised; the names are filled in as the definitions below initialise, before main).
const bool g_registered = (gphr::setMpiTimeSource(&counters), gphr::setMpiCallNames(g_kindNames),
                           gphr::setCriticalPathMeasured(std::getenv("GPHR_CRITICAL_PATH") &&
                                                         std::string(std::getenv("GPHR_CRITICAL_PATH")) == "1"),
                           true);
const long long g_startNs = nanoseconds(CLOCK_MONOTONIC);

// GPHR_PROCESS_CLOCKS=PREFIX: this rank's whole-process line into PREFIX.RANK (see the top).
void writeProcessClocks() {
  const char* prefix = std::getenv("GPHR_PROCESS_CLOCKS");
  if (!prefix || !*prefix) return;
  int rank = 0;
  PMPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (gphr::criticalPathMeasured()) {  // the whole run's critical path: agreed on once more at the end
    g_criticalNs.fetch_add(nanoseconds(CLOCK_THREAD_CPUTIME_ID) - t_lastExitCpuNs, std::memory_order_relaxed);
    t_lastExitCpuNs = nanoseconds(CLOCK_THREAD_CPUTIME_ID);
    agreeOnCriticalPath(MPI_COMM_WORLD);
  }
  const gphr::MpiTime mpi = counters();
  const double wall = 1e-9 * static_cast<double>(nanoseconds(CLOCK_MONOTONIC) - g_startNs);
  const double cpu = 1e-9 * static_cast<double>(nanoseconds(CLOCK_PROCESS_CPUTIME_ID));
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  const std::string path = std::string(prefix) + "." + std::to_string(rank);
  if (FILE* f = std::fopen(path.c_str(), "w")) {
    std::fprintf(f, "%d,process,%.6f,%.6f,%.6f,%.6f,%.6f,%.1f,%.6f\n", rank, wall, cpu, mpi.wall, mpi.cpu,
                 cpu - mpi.cpu, static_cast<double>(u.ru_maxrss) / 1024.0, mpi.critical);
    std::fclose(f);
  } else {
    std::fprintf(stderr, "[gphr] GPHR_PROCESS_CLOCKS: cannot write '%s'\n", path.c_str());
  }
}

}  // namespace

// MPI_NAME(PARAMS) { PMPI_NAME(ARGS), timed as a kind of its own }. __COUNTER__ numbers the
// definitions 0, 1, ... from kFirstKind on.
constexpr int kFirstKind = __COUNTER__ + 1;
#define GPHR_TIMED(NAME, PARAMS, ARGS) GPHR_TIMED_KIND(NAME, PARAMS, ARGS, __COUNTER__ - kFirstKind, MPI_COMM_NULL)
// A collective call: its parameter `comm` is where the critical path is agreed on.
#define GPHR_COLLECTIVE(NAME, PARAMS, ARGS) GPHR_TIMED_KIND(NAME, PARAMS, ARGS, __COUNTER__ - kFirstKind, comm)
#define GPHR_TIMED_KIND(NAME, PARAMS, ARGS, KIND, COMM)                                \
  static_assert(KIND < gphr::kMpiCallKinds, "more MPI functions than gphr::kMpiCallKinds"); \
  static const int g_kind_##NAME = nameKind(KIND, "MPI_" #NAME);                       \
  extern "C" int MPI_##NAME PARAMS {                                                   \
    const TimedCall timed(g_kind_##NAME, COMM);                                        \
    return PMPI_##NAME ARGS;                                                           \
  }

GPHR_COLLECTIVE(Allgather, (const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
           MPI_Datatype recvtype, MPI_Comm comm), (sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm))
GPHR_COLLECTIVE(Allgatherv, (const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, const int
           recvcounts[], const int displs[], MPI_Datatype recvtype, MPI_Comm comm), (sendbuf, sendcount, sendtype,
           recvbuf, recvcounts, displs, recvtype, comm))
GPHR_COLLECTIVE(Allreduce, (const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype, MPI_Op op, MPI_Comm
           comm), (sendbuf, recvbuf, count, datatype, op, comm))
GPHR_COLLECTIVE(Alltoall, (const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
           MPI_Datatype recvtype, MPI_Comm comm), (sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm))
GPHR_COLLECTIVE(Alltoallv, (const void *sendbuf, const int sendcounts[], const int sdispls[], MPI_Datatype sendtype, void
           *recvbuf, const int recvcounts[], const int rdispls[], MPI_Datatype recvtype, MPI_Comm comm), (sendbuf,
           sendcounts, sdispls, sendtype, recvbuf, recvcounts, rdispls, recvtype, comm))
GPHR_COLLECTIVE(Alltoallw, (const void *sendbuf, const int sendcounts[], const int sdispls[], const MPI_Datatype
           sendtypes[], void *recvbuf, const int recvcounts[], const int rdispls[], const MPI_Datatype recvtypes[],
           MPI_Comm comm), (sendbuf, sendcounts, sdispls, sendtypes, recvbuf, recvcounts, rdispls, recvtypes, comm))
GPHR_COLLECTIVE(Barrier, (MPI_Comm comm), (comm))
GPHR_COLLECTIVE(Bcast, (void *buffer, int count, MPI_Datatype datatype, int root, MPI_Comm comm), (buffer, count, datatype,
           root, comm))
GPHR_COLLECTIVE(Exscan, (const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype, MPI_Op op, MPI_Comm comm),
           (sendbuf, recvbuf, count, datatype, op, comm))
GPHR_COLLECTIVE(Gather, (const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
           MPI_Datatype recvtype, int root, MPI_Comm comm), (sendbuf, sendcount, sendtype, recvbuf, recvcount,
           recvtype, root, comm))
GPHR_COLLECTIVE(Gatherv, (const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, const int recvcounts[],
           const int displs[], MPI_Datatype recvtype, int root, MPI_Comm comm), (sendbuf, sendcount, sendtype,
           recvbuf, recvcounts, displs, recvtype, root, comm))
GPHR_COLLECTIVE(Reduce, (const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype, MPI_Op op, int root,
           MPI_Comm comm), (sendbuf, recvbuf, count, datatype, op, root, comm))
GPHR_COLLECTIVE(Reduce_scatter, (const void *sendbuf, void *recvbuf, const int recvcounts[], MPI_Datatype datatype, MPI_Op
           op, MPI_Comm comm), (sendbuf, recvbuf, recvcounts, datatype, op, comm))
GPHR_COLLECTIVE(Reduce_scatter_block, (const void *sendbuf, void *recvbuf, int recvcount, MPI_Datatype datatype, MPI_Op op,
           MPI_Comm comm), (sendbuf, recvbuf, recvcount, datatype, op, comm))
GPHR_COLLECTIVE(Scan, (const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype, MPI_Op op, MPI_Comm comm),
           (sendbuf, recvbuf, count, datatype, op, comm))
GPHR_COLLECTIVE(Scatter, (const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
           MPI_Datatype recvtype, int root, MPI_Comm comm), (sendbuf, sendcount, sendtype, recvbuf, recvcount,
           recvtype, root, comm))
GPHR_COLLECTIVE(Scatterv, (const void *sendbuf, const int sendcounts[], const int displs[], MPI_Datatype sendtype, void
           *recvbuf, int recvcount, MPI_Datatype recvtype, int root, MPI_Comm comm), (sendbuf, sendcounts, displs,
           sendtype, recvbuf, recvcount, recvtype, root, comm))
GPHR_TIMED(Send, (const void *buf, int count, MPI_Datatype datatype, int dest, int tag, MPI_Comm comm), (buf, count,
           datatype, dest, tag, comm))
GPHR_TIMED(Ssend, (const void *buf, int count, MPI_Datatype datatype, int dest, int tag, MPI_Comm comm), (buf, count,
           datatype, dest, tag, comm))
GPHR_TIMED(Rsend, (const void *ibuf, int count, MPI_Datatype datatype, int dest, int tag, MPI_Comm comm), (ibuf,
           count, datatype, dest, tag, comm))
GPHR_TIMED(Bsend, (const void *buf, int count, MPI_Datatype datatype, int dest, int tag, MPI_Comm comm), (buf, count,
           datatype, dest, tag, comm))
GPHR_TIMED(Recv, (void *buf, int count, MPI_Datatype datatype, int source, int tag, MPI_Comm comm, MPI_Status
           *status), (buf, count, datatype, source, tag, comm, status))
GPHR_TIMED(Sendrecv, (const void *sendbuf, int sendcount, MPI_Datatype sendtype, int dest, int sendtag, void *recvbuf,
           int recvcount, MPI_Datatype recvtype, int source, int recvtag, MPI_Comm comm, MPI_Status *status),
           (sendbuf, sendcount, sendtype, dest, sendtag, recvbuf, recvcount, recvtype, source, recvtag, comm, status))
GPHR_TIMED(Sendrecv_replace, (void * buf, int count, MPI_Datatype datatype, int dest, int sendtag, int source, int
           recvtag, MPI_Comm comm, MPI_Status *status), (buf, count, datatype, dest, sendtag, source, recvtag, comm,
           status))
GPHR_TIMED(Probe, (int source, int tag, MPI_Comm comm, MPI_Status *status), (source, tag, comm, status))
GPHR_TIMED(Iprobe, (int source, int tag, MPI_Comm comm, int *flag, MPI_Status *status), (source, tag, comm, flag,
           status))
GPHR_TIMED(Mprobe, (int source, int tag, MPI_Comm comm, MPI_Message *message, MPI_Status *status), (source, tag, comm,
           message, status))
GPHR_TIMED(Wait, (MPI_Request *request, MPI_Status *status), (request, status))
GPHR_TIMED(Waitall, (int count, MPI_Request array_of_requests[], MPI_Status *array_of_statuses), (count,
           array_of_requests, array_of_statuses))
GPHR_TIMED(Waitany, (int count, MPI_Request array_of_requests[], int *index, MPI_Status *status), (count,
           array_of_requests, index, status))
GPHR_TIMED(Waitsome, (int incount, MPI_Request array_of_requests[], int *outcount, int array_of_indices[], MPI_Status
           array_of_statuses[]), (incount, array_of_requests, outcount, array_of_indices, array_of_statuses))
GPHR_TIMED(Test, (MPI_Request *request, int *flag, MPI_Status *status), (request, flag, status))
GPHR_TIMED(Testall, (int count, MPI_Request array_of_requests[], int *flag, MPI_Status array_of_statuses[]), (count,
           array_of_requests, flag, array_of_statuses))
GPHR_COLLECTIVE(Comm_split, (MPI_Comm comm, int color, int key, MPI_Comm *newcomm), (comm, color, key, newcomm))
GPHR_COLLECTIVE(Comm_dup, (MPI_Comm comm, MPI_Comm *newcomm), (comm, newcomm))
GPHR_COLLECTIVE(Comm_create, (MPI_Comm comm, MPI_Group group, MPI_Comm *newcomm), (comm, group, newcomm))
GPHR_COLLECTIVE(Comm_split_type, (MPI_Comm comm, int split_type, int key, MPI_Info info, MPI_Comm *newcomm), (comm,
           split_type, key, info, newcomm))
GPHR_COLLECTIVE(File_open, (MPI_Comm comm, const char *filename, int amode, MPI_Info info, MPI_File *fh), (comm, filename,
           amode, info, fh))
GPHR_TIMED(File_close, (MPI_File *fh), (fh))
GPHR_TIMED(File_read_at, (MPI_File fh, MPI_Offset offset, void *buf, int count, MPI_Datatype datatype, MPI_Status
           *status), (fh, offset, buf, count, datatype, status))
GPHR_TIMED(File_read_at_all, (MPI_File fh, MPI_Offset offset, void *buf, int count, MPI_Datatype datatype, MPI_Status
           *status), (fh, offset, buf, count, datatype, status))
GPHR_TIMED(File_write_at, (MPI_File fh, MPI_Offset offset, const void *buf, int count, MPI_Datatype datatype,
           MPI_Status *status), (fh, offset, buf, count, datatype, status))
GPHR_TIMED(File_write_at_all, (MPI_File fh, MPI_Offset offset, const void *buf, int count, MPI_Datatype datatype,
           MPI_Status *status), (fh, offset, buf, count, datatype, status))
GPHR_TIMED(File_set_view, (MPI_File fh, MPI_Offset disp, MPI_Datatype etype, MPI_Datatype filetype, const char
           *datarep, MPI_Info info), (fh, disp, etype, filetype, datarep, info))
GPHR_TIMED(File_set_size, (MPI_File fh, MPI_Offset size), (fh, size))
GPHR_TIMED(File_get_size, (MPI_File fh, MPI_Offset *size), (fh, size))
GPHR_TIMED(File_sync, (MPI_File fh), (fh))
GPHR_TIMED(Win_fence, (int mode, MPI_Win win), (mode, win))

extern "C" int MPI_Finalize() {
  writeProcessClocks();
  return PMPI_Finalize();
}

#undef GPHR_TIMED
#undef GPHR_COLLECTIVE
#undef GPHR_TIMED_KIND
