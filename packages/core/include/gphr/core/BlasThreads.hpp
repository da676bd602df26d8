#pragma once
/// @file
/// OpenBLAS on one thread while a scope lives (SingleBlasThread). OpenBLAS splits a large enough
/// BLAS call over its threads, and the split changes the order of the additions, so a result's
/// last bits depend on OPENBLAS_NUM_THREADS; a reduced model's few-thousand-flop calls gain nothing
/// from threads anyway. `gphr query` and ReducedModel (set-up and time loop) run under one, so a
/// query gives the same bits whatever the thread count. Where the BLAS is not OpenBLAS nothing is
/// done (weak symbols).
namespace gphr {

/// See the file's description. Where OpenBLAS already runs one thread it does nothing, so scopes
/// nest and the workers of a thread pool that pinned it before starting (forEachOnThreads) never
/// call OpenBLAS's setter concurrently; a code that runs queries on threads of its own should pin
/// it the same way, once, before starting them.
class SingleBlasThread {
 public:
  SingleBlasThread();
  ~SingleBlasThread();  ///< restores the thread count it found
  SingleBlasThread(const SingleBlasThread&) = delete;
  SingleBlasThread& operator=(const SingleBlasThread&) = delete;

 private:
  int before_ = 0;  ///< the count it found; 0: nothing to restore
};

/// OpenBLAS's thread count now (0 where the BLAS is not OpenBLAS).
int blasThreads();
/// Sets OpenBLAS's thread count (nothing where the BLAS is not OpenBLAS). Not from two threads at once.
void setBlasThreads(int threads);

}  // namespace gphr
