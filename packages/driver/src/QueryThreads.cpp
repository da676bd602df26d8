#include "gphr/driver/QueryThreads.hpp"

#include <mpi.h>
#include <sched.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <map>
#include <mutex>
#include <thread>
#include <vector>

#include "gphr/core/BlasThreads.hpp"
#include "gphr/core/Error.hpp"
#include "gphr/core/ThreadTimers.hpp"

namespace gphr {

int queryThreadsFromText(const std::string& text) {
  size_t used = 0;
  long n = 0;
  try {
    n = std::stol(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  GPHR_REQUIRE(used == text.size() && used > 0 && n >= 1 && n <= kMaxQueryThreads, InputError, "--threads '", text,
               "' is not allowed (allowed: an integer from 1 to ", kMaxQueryThreads, ")");
  return static_cast<int>(n);
}

int defaultQueryThreads() {
  cpu_set_t set;
  CPU_ZERO(&set);
  const int allowed = sched_getaffinity(0, sizeof set, &set) == 0 ? CPU_COUNT(&set) : 1;
  const int machine = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int onNode = 1;
  MPI_Comm_size(node, &onNode);
  MPI_Comm_free(&node);
  return std::max(1, allowed >= machine ? allowed / onNode : allowed);
}

void forEachOnThreads(size_t n, int threads, const std::function<void(size_t)>& fn) {
  const SingleBlasThread blas;  // before the workers start: they never set it concurrently
  if (threads <= 1) {
    for (size_t i = 0; i < n; ++i) fn(i);
    return;
  }
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex m;
  std::map<size_t, std::exception_ptr> errors;
  auto work = [&] {
    const WithoutProcessTimers noTimers;
    for (size_t i; !failed && (i = next++) < n;) {
      try {
        fn(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(m);
        errors.emplace(i, std::current_exception());
        failed = true;
      }
    }
  };
  std::vector<std::thread> pool;
  for (size_t t = 0; t < std::min<size_t>(threads, n); ++t) pool.emplace_back(work);
  for (auto& t : pool) t.join();
  if (!errors.empty()) std::rethrow_exception(errors.begin()->second);
}

}  // namespace gphr
