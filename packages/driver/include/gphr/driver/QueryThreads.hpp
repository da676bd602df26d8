#pragma once
/// @file
/// The threads of `gphr query --threads N`: how many by default, the option's check, and a loop
/// over a rank's queries on a pool of std::threads.
#include <cstddef>
#include <functional>
#include <string>

namespace gphr {

constexpr int kMaxQueryThreads = 1024;  ///< --threads at most

/// --threads TEXT: an integer from 1 to kMaxQueryThreads, else InputError naming TEXT and the range.
int queryThreadsFromText(const std::string& text);

/// The default --threads of this rank (collective over MPI_COMM_WORLD): the CPUs its affinity mask
/// allows (sched_getaffinity); when that is every CPU of the machine (ranks not bound), shared
/// evenly with the other ranks on its node (MPI_COMM_TYPE_SHARED). At least 1.
int defaultQueryThreads();

/// fn(i) for every i in [0, n), each i once, on `threads` std::threads that each take the next i
/// (on the calling thread when threads == 1). Worker threads keep no process-wide timers
/// (ThreadTimers.hpp). OpenBLAS runs on one thread meanwhile, whatever `threads`: the pool is the
/// parallelism (OpenBLAS's own threads would oversubscribe the cores), and its multithreaded
/// kernels sum in another order, so fn's results would depend on `threads` at round-off level
/// (measured: 1e-15 in H_hr). After an exception no new i is started; once all
/// threads stopped, the exception of the smallest failed i is rethrown (the one a single thread
/// would have met first).
void forEachOnThreads(size_t n, int threads, const std::function<void(size_t)>& fn);

}  // namespace gphr
