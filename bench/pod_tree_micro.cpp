// Micro-benchmark of the streaming POD's per-step work beyond each rank's own rows: the stacked
// route (every rank takes the GESDD of the p c x c stack of R factors) against the tree route (a
// binary tree of 2c x c QRs, one c x c GESDD on rank 0, the tree's Q applied back down), at the
// rank count it is started on. Each rank holds `rowsPerRank` rows; after the first steps every
// step has c = maxRank + block columns (carried + new). Per route: wall seconds per step (slowest
// rank, the median of `repeats` POD runs, the routes alternating so both see the same load; the
// average over all steps, the first ones narrower) and the flop model of a full step's small
// factorizations that every rank waits for (a c x c GESDD with vectors counted as 8 c^3):
//   stacked: GESDD of pc x c ~ (8 + 4 (p - 1)) c^3 (the c x c one plus the QR of the taller stack
//   and its Q applied); tree: ~ (8 + 3 ceil(log2 p)) c^3 (per level the TPQRT of two triangles,
//   about c^3 with its T factor, and its TPMQRT on the way down, about 2 c^3 for c columns; with
//   GEQRF/ORMQR of the dense 2c x c stack it was 10/3 + 4 = 22/3 c^3).
// The local GEQRF/ORMQR of each rank's rows (rowsPerRank c^2) is the same on both routes.
// With `kernels` it times those small factorizations alone on one core instead, for any p (the
// critical path of one step beyond the local rows; the steadier figure on a loaded machine):
// stacked: GESDD of the p c x c stack of triangles; tree: ceil(log2 p) x (TPQRT of two stacked
// triangles, its R, TPMQRT of c columns) and a c x c GESDD, and the same with GEQRF/ORMQR of the
// dense 2c x c stack at each level. CPU seconds, median of REPEATS.
// With `leaf` it times one rank's own rows instead, the part of a step that divides with the ranks:
// the QR of ROWS x C and Q [W; 0] for KEEP columns, by LAPACK GEQRF and ORMQR of the whole block
// against HouseholderQr's row chunks (GEQRT, TPQRT, and their Q). On one core, or as many copies
// side by side as it is started with (mpirun -np P: P ranks share the memory bandwidth as a
// P-rank build's leaves do); CPU seconds, median of REPEATS, the slowest rank's.
// usage: mpirun -np P pod_tree_micro [ROWS_PER_RANK=4096] [MAXRANK=192] [BLOCK=64] [STEPS=6] [REPEATS=3]
//        pod_tree_micro kernels [C=256] [REPEATS=5]
//        [mpirun -np P] pod_tree_micro leaf [ROWS=65536] [C=232] [KEEP=112] [REPEATS=5]
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_LAPACK.hpp>
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <ctime>
#include <vector>

#include "gphr/reduction/DenseSvd.hpp"
#include "gphr/reduction/StreamingPod.hpp"
#include "gphr/reduction/TreeTsqr.hpp"

namespace {
using namespace gphr;

// Random snapshots with a decaying spectrum (column j scaled by 0.97^j), the same on any rank count.
MultiVector snapshots(const RCP<const Map>& map, int columns) {
  MultiVector X(map, columns);
  auto x = X.getLocalViewHost(Tpetra::Access::OverwriteAll);
  for (LO l = 0; l < static_cast<LO>(map->getNodeNumElements()); ++l) {
    std::mt19937 gen(static_cast<unsigned>(map->getGlobalElement(l)));
    std::normal_distribution<double> N(0.0, 1.0);
    for (int j = 0; j < columns; ++j) x(l, j) = N(gen) * std::pow(0.97, j);
  }
  return X;
}

// Wall seconds of one POD over X by `route`, the slowest rank's.
double podSeconds(const MultiVector& X, int maxRank, int block, PodRoute route) {
  const auto& comm = *X.getMap()->getComm();
  comm.barrier();
  const auto t0 = std::chrono::steady_clock::now();
  StreamingPod pod(X.getMap(), maxRank, block, 0.0, route);
  pod.add(X);
  const double mine = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  double slowest = 0.0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, mine, Teuchos::outArg(slowest));
  return slowest;
}
double cpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// p random c x c upper triangles stacked (pc x c, column-major).
std::vector<double> triangles(int p, int c, std::mt19937& gen) {
  std::normal_distribution<double> N(0.0, 1.0);
  std::vector<double> a(static_cast<size_t>(p) * c * c, 0.0);
  for (int q = 0; q < p; ++q)
    for (int j = 0; j < c; ++j)
      for (int i = 0; i <= j; ++i) a[q * c + i + static_cast<size_t>(p) * c * j] = N(gen);
  return a;
}

template <class Fn>
double medianCpu(int repeats, Fn&& fn) {
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const double t0 = cpuSeconds();
    fn();
    t.push_back(cpuSeconds() - t0);
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

// The QR as HouseholderQr took it before its row chunks, the baseline of `leaf` and of the
// tree's dense levels in `kernels`: LAPACK GEQRF of the whole m x n block, Q [C; 0] by ORMQR.
struct GeqrfQr {
  int m, n;
  std::vector<double> a, tau;
  GeqrfQr(int rows, int cols, std::vector<double> block) : m(rows), n(cols), a(std::move(block)), tau(cols) {
    Teuchos::LAPACK<int, double> lapack;
    std::vector<double> work(1);
    int info = 0;
    lapack.GEQRF(m, n, a.data(), m, tau.data(), work.data(), -1, &info);
    work.resize(static_cast<size_t>(work[0]));
    lapack.GEQRF(m, n, a.data(), m, tau.data(), work.data(), static_cast<int>(work.size()), &info);
  }
  std::vector<double> r() const {
    std::vector<double> R(static_cast<size_t>(n) * n, 0.0);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i <= j; ++i) R[i + static_cast<size_t>(n) * j] = a[i + static_cast<size_t>(m) * j];
    return R;
  }
  std::vector<double> applyQ(const std::vector<double>& C, int cols) const {
    std::vector<double> out(static_cast<size_t>(m) * cols, 0.0), work(1);
    for (int j = 0; j < cols; ++j) std::copy_n(C.begin() + static_cast<size_t>(n) * j, n, out.begin() + static_cast<size_t>(m) * j);
    Teuchos::LAPACK<int, double> lapack;
    int info = 0;
    auto* v = const_cast<double*>(a.data());  // ORMQR reads them; Teuchos declares them non-const
    auto* t = const_cast<double*>(tau.data());
    lapack.ORMQR('L', 'N', m, cols, n, v, m, t, out.data(), m, work.data(), -1, &info);
    work.resize(static_cast<size_t>(work[0]));
    lapack.ORMQR('L', 'N', m, cols, n, v, m, t, out.data(), m, work.data(), static_cast<int>(work.size()), &info);
    return out;
  }
};

// One rank's leaf: QR of rows x c and Q [W; 0] for keep columns, GEQRF/ORMQR against HouseholderQr,
// alternating so that both see the same load; prints the slowest rank's medians and |R| agreement.
void leaf(int rows, int c, int keep, int repeats) {
  const auto comm = Tpetra::getDefaultComm();
  std::mt19937 gen(5 + comm->getRank());
  std::normal_distribution<double> N(0.0, 1.0);
  std::vector<double> block(static_cast<size_t>(rows) * c), W(static_cast<size_t>(c) * keep);
  for (double& x : block) x = N(gen);
  for (double& x : W) x = N(gen);
  std::vector<double> geqrf, chunked;
  double rdiff = 0.0;
  for (int r = 0; r < repeats; ++r) {
    std::vector<double> Rg, Rc;
    comm->barrier();
    geqrf.push_back(medianCpu(1, [&] {
      const GeqrfQr qr(rows, c, block);
      Rg = qr.r();
      qr.applyQ(W, keep);
    }));
    comm->barrier();
    chunked.push_back(medianCpu(1, [&] {
      const HouseholderQr qr(rows, c, block);
      Rc = qr.r();
      qr.applyQ(W, keep);
    }));
    for (int i = 0; i < c; ++i)  // R is unique up to its rows' signs
      for (int j = i; j < c; ++j)
        rdiff = std::max(rdiff, std::abs(std::abs(Rg[i + static_cast<size_t>(c) * j]) - std::abs(Rc[i + static_cast<size_t>(c) * j])));
  }
  for (auto* t : {&geqrf, &chunked}) std::sort(t->begin(), t->end());
  double g = geqrf[repeats / 2], h = chunked[repeats / 2], gmax = 0.0, hmax = 0.0, dmax = 0.0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, g, Teuchos::outArg(gmax));
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, h, Teuchos::outArg(hmax));
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, rdiff, Teuchos::outArg(dmax));
  if (comm->getRank() == 0)
    std::printf("leaf %d x %d, Q applied to %d columns, %d cop%s side by side (CPU s, median of %d, slowest): "
                "GEQRF+ORMQR %.4f s, row chunks of %d (GEQRT+TPQRT) %.4f s, ratio %.2f; max ||R_ij| - |R'_ij|| %.1e\n",
                rows, c, keep, comm->getSize(), comm->getSize() == 1 ? "y" : "ies", repeats, gmax,
                HouseholderQr::kChunkRows, hmax, gmax / hmax, dmax);
}

void kernels(int c, int repeats) {
  std::mt19937 gen(3);
  std::printf("one step's small factorizations on one core, c = %d (CPU s, median of %d):\n", c, repeats);
  for (int p : {1, 2, 3, 4, 8, 16, 32, 64}) {
    const int K = p * c, levels = static_cast<int>(std::ceil(std::log2(p)));
    std::vector<double> S(c), W(static_cast<size_t>(K) * c), Zt(static_cast<size_t>(c) * c);
    const std::vector<double> stack = triangles(p, c, gen), pair = triangles(2, c, gen), root = triangles(1, c, gen);
    const double stacked = medianCpu(repeats, [&] {
      std::vector<double> a = stack;
      denseThinSvd(K, c, a.data(), K, S.data(), W.data(), K, Zt.data(), c, true, "bench");
    });
    // The tree's levels as TreeTsqr takes them (TPQRT of two triangles) and, for comparison, as
    // GEQRF/ORMQR of the dense 2c x c stack (the tree's levels before the structured QR).
    auto tree = [&](bool structured) {
      return medianCpu(repeats, [&] {
        std::vector<double> C(static_cast<size_t>(c) * c, 1.0);
        for (int l = 0; l < levels; ++l) {
          if (structured) {
            const TriangleStackQr qr(c, std::vector<double>(root), c, std::vector<double>(root));
            const std::vector<double> R = qr.r();
            C = qr.applyQ(C, c);
          } else {
            const GeqrfQr qr(2 * c, c, pair);
            const std::vector<double> R = qr.r();
            C = qr.applyQ(C, c);
          }
          C.resize(static_cast<size_t>(c) * c);  // the top c rows go on down
        }
        std::vector<double> a = root;
        denseThinSvd(c, c, a.data(), c, S.data(), W.data(), c, Zt.data(), c, true, "bench");
      });
    };
    const double treeTp = tree(true), treeDense = tree(false);
    std::printf("  p = %2d: stacked %.4f s, tree %.4f s (with dense GEQRF levels %.4f s), stacked/tree %.2f\n", p,
                stacked, treeTp, treeDense, stacked / treeTp);
  }
}
}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "kernels") {
    kernels(argc > 2 ? std::atoi(argv[2]) : 256, argc > 3 ? std::atoi(argv[3]) : 5);
    return 0;
  }
  Tpetra::ScopeGuard scope(&argc, &argv);
  if (argc > 1 && std::string(argv[1]) == "leaf") {
    leaf(argc > 2 ? std::atoi(argv[2]) : 65536, argc > 3 ? std::atoi(argv[3]) : 232, argc > 4 ? std::atoi(argv[4]) : 112,
         argc > 5 ? std::atoi(argv[5]) : 5);
    return 0;
  }
  const auto comm = Tpetra::getDefaultComm();
  const int rowsPerRank = argc > 1 ? std::atoi(argv[1]) : 4096, maxRank = argc > 2 ? std::atoi(argv[2]) : 192;
  const int block = argc > 3 ? std::atoi(argv[3]) : 64, steps = argc > 4 ? std::atoi(argv[4]) : 6;
  const int repeats = argc > 5 ? std::atoi(argv[5]) : 3, p = comm->getSize();
  const auto map = rcp(new Map(static_cast<GO>(rowsPerRank) * p, 0, comm));
  // maxRank / block steps fill the carried rank; `steps` more run at c = maxRank + block.
  const int fill = (maxRank + block - 1) / block;
  const MultiVector X = snapshots(map, (fill + steps) * block);
  std::vector<double> stacked, tree;
  for (int r = 0; r < repeats; ++r) {
    stacked.push_back(podSeconds(X, maxRank, block, PodRoute::Stacked));
    tree.push_back(podSeconds(X, maxRank, block, PodRoute::Tree));
  }
  for (auto* t : {&stacked, &tree}) std::sort(t->begin(), t->end());
  const double c = maxRank + block, c3 = c * c * c, levels = std::ceil(std::log2(p));
  const double perStep = 1.0 / (fill + steps);
  if (comm->getRank() == 0)
    std::printf("p = %d, %d rows per rank, c = %.0f: average step stacked %.4f s, tree %.4f s (stacked/tree %.2f); "
                "flop model of the small factorizations: stacked %.2e, tree %.2e (%.2f)\n",
                p, rowsPerRank, c, stacked[repeats / 2] * perStep, tree[repeats / 2] * perStep,
                stacked[repeats / 2] / tree[repeats / 2], (8.0 + 4.0 * (p - 1)) * c3,
                (8.0 + 3.0 * levels) * c3, (8.0 + 4.0 * (p - 1)) / (8.0 + 3.0 * levels));
  return 0;
}
