#include "gphr/core/BlasThreads.hpp"

// OpenBLAS's thread count, where the BLAS is OpenBLAS (weak: absent with another BLAS).
extern "C" void openblas_set_num_threads(int) __attribute__((weak));
extern "C" int openblas_get_num_threads() __attribute__((weak));

namespace gphr {

int blasThreads() { return openblas_get_num_threads ? openblas_get_num_threads() : 0; }

void setBlasThreads(int threads) {
  if (openblas_set_num_threads) openblas_set_num_threads(threads);
}

SingleBlasThread::SingleBlasThread() {
  const int now = blasThreads();
  if (now > 1) {
    before_ = now;
    setBlasThreads(1);
  }
}

SingleBlasThread::~SingleBlasThread() {
  if (before_ > 0) setBlasThreads(before_);
}

}  // namespace gphr
