// The GP-DEIM query path allocates nothing of size n or d: every heap
// allocation of this process goes through the malloc family below, which records the largest
// request made while a region is tracked. Loading a reduced-model file, instantiating a model at a
// parameter (interpolated set-up) and running it must stay far below one vector of size d = n;
// the exact set-up route, which builds the full system at the parameter, must not (so the
// detector is shown to see an n-sized allocation in this very test).
#include <gtest/gtest.h>
#include <errno.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdio>

#include "TestUtils.hpp"
#include "gphr/offline/ModelFileBuilder.hpp"
#include "gphr/online/ReducedModel.hpp"

namespace {
std::atomic<bool> tracking{false};
std::atomic<size_t> largest{0};
void note(size_t n) {
  if (tracking.load(std::memory_order_relaxed) && n > largest.load(std::memory_order_relaxed)) largest = n;
}
}  // namespace

// glibc's own entry points, forwarded to after recording the size (free needs no wrapper).
extern "C" {
void* __libc_malloc(size_t);
void* __libc_calloc(size_t, size_t);
void* __libc_realloc(void*, size_t);
void* __libc_memalign(size_t, size_t);
void* malloc(size_t n) {
  note(n);
  return __libc_malloc(n);
}
void* calloc(size_t a, size_t b) {
  note(a * b);
  return __libc_calloc(a, b);
}
void* realloc(void* p, size_t n) {
  note(n);
  return __libc_realloc(p, n);
}
void* memalign(size_t alignment, size_t n) {
  note(n);
  return __libc_memalign(alignment, n);
}
void* aligned_alloc(size_t alignment, size_t n) {
  note(n);
  return __libc_memalign(alignment, n);
}
int posix_memalign(void** out, size_t alignment, size_t n) {
  note(n);
  *out = __libc_memalign(alignment, n);
  return *out ? 0 : ENOMEM;
}
}

using namespace gphr;

namespace {

const int kK = 5, kM = 10;

// Column c: sin((c + 1) 0.37 g + 0.1 c) at global id g, scaled: distinct frequencies, so the
// columns are independent (on any rank count).
void fillColumns(MultiVector& X, double scale) {
  auto map = X.getMap();
  auto v = X.getLocalViewHost(Tpetra::Access::OverwriteAll);
  for (size_t c = 0; c < X.getNumVectors(); ++c)
    for (LO i = 0; i < static_cast<LO>(map->getNodeNumElements()); ++i)
      v(i, c) = scale * std::sin((c + 1) * 0.37 * map->getGlobalElement(i) + 0.1 * c);
}

// A synthetic basis and DEIM basis (the query path does not care how they were computed).
std::string writeModel(const Nls1d& scene, bool withBasis) {
  auto inst = scene.instantiate(test::comm(), {1.0}, true);
  MultiVector A(inst.system->map(), 2 * kK), U(inst.system->nonlinearTerm().rowMap(), kM);
  fillColumns(A, 1.0 / std::sqrt(double(scene.n())));
  fillColumns(U, 1.0);
  ModelFileOptions opt;
  ReducedModelData data = modelFileHeader(scene, inst, opt);
  data.T = 0.05, data.dt = 0.01;
  addReducedBasis(data, scene, inst, A, kK, U, {kM}, opt);
  const std::string path = "/tmp/gphr-test-memory-" + std::to_string(getpid()) + "-" + std::to_string(scene.n()) +
                           (withBasis ? "-A" : "") + ".h5";
  writeReducedModelFile(path, test::comm(), data, {withBasis ? rcp(new MultiVector(A)) : Teuchos::null},
                        &inst.system->space());
  return path;
}

// The largest single allocation of: load the file, instantiate at eps = 1.03, run 5 steps.
size_t largestAllocationOfAQuery(const std::string& path, const std::shared_ptr<const Scene>& scene, SetupRoute route) {
  largest = 0;
  tracking = true;
  {
    ReducedModel rm(path, scene);
    auto online = rm.instantiate("gp-deim", kK, kM, {1.03}, false, route);
    online.simulate(0.05, 0.01, [](const QueryStep&) {});
  }
  tracking = false;
  return largest;
}

struct Largest {
  size_t interpolated = 0, exact = 0, vectorOfD = 0;
};

Largest measure(GO n) {
  auto scene = std::make_shared<Nls1d>(n);
  const std::string path = writeModel(*scene, true);
  largestAllocationOfAQuery(path, scene, SetupRoute::Interpolated);  // warm-up: libraries' one-time buffers
  Largest out;
  out.interpolated = largestAllocationOfAQuery(path, scene, SetupRoute::Interpolated);
  out.exact = largestAllocationOfAQuery(path, scene, SetupRoute::Exact);
  out.vectorOfD = sizeof(double) * n;
  std::printf("n = %lld: largest allocation of a query: interpolated set-up %zu bytes, exact set-up %zu bytes; one "
              "vector of size d: %zu bytes\n", static_cast<long long>(n), out.interpolated, out.exact, out.vectorOfD);
  std::remove(path.c_str());
  return out;
}

}  // namespace

TEST(QueryMemory, TheGpDeimQueryPathAllocatesNothingOfSizeNOrD) {
  const Largest small = measure(GO(1) << 17), large = measure(GO(1) << 19);
  // The largest request of the interpolated route is the HDF5 library's metadata cache (516 kB at
  // every file open, whatever the file): it does not grow with n. 4 kB of slack for names.
  EXPECT_LE(large.interpolated, small.interpolated + 4096);
  // And it is far below one vector of size d = n at the larger size (4 MiB): any array of size
  // n, d or 2n fails this.
  EXPECT_LT(large.interpolated, large.vectorOfD / 4);
  // The detector sees the exact route's full system (states of 2n doubles), at both sizes.
  EXPECT_GE(small.exact, 2 * small.vectorOfD);
  EXPECT_GE(large.exact, 2 * large.vectorOfD);
}
