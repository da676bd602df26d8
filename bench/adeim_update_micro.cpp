// Micro-benchmark of one GP-ADEIM update's dense algebra at the paper's NLS size (m = 100,
// wbar = 2k w = 400, m_s = 250, one rank): factorCoefficients (C_j and its rank-revealing factor)
// and computeAdeimUpdate (the rank-r update, r by tau_r = 1e-12), on random data. Wall time per
// call, the median of repeated calls (run it with OPENBLAS_NUM_THREADS=1 for the benchmark's
// setting), printed side by side; then a roofline line per kernel: its flops and the bytes of its
// inputs and outputs, counted from the sizes (leading-order LAPACK counts, LAWN 41: GETRF 2/3 m^3,
// GETRI 4/3 m^3, a Householder QR of a p x q matrix 2 p q^2 - 2/3 q^3, TRTRI 1/3 q^3, forming a
// p x q Q by ORMQR 4 p q^2 - 2 q^3, singular values alone 8/3 q^3), its GFlop/s, and that as a
// share of this machine's DGEMM measured at the kernels' largest product (S^T U C: 250 x 100 times
// 100 x 400). The counts assume full rank (r_C = m, r = r_C, as the random data give; a smaller r
// adds an SVD with vectors that is not counted). Intensities of ~25 flop per byte of data that
// fits in cache make both compute-bound in principle: the share of DGEMM is what overhead (small
// calls, unblocked LAPACK paths, copies) costs.
// usage: adeim_update_micro [REPEATS]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include <Teuchos_BLAS.hpp>

#include "gphr/hyper/AdeimUpdate.hpp"

namespace {
gphr::DenseMatrix randomMatrix(int r, int c, std::mt19937& gen) {
  std::normal_distribution<double> N(0.0, 1.0);
  gphr::DenseMatrix A(r, c);
  for (int j = 0; j < c; ++j)
    for (int i = 0; i < r; ++i) A(i, j) = N(gen);
  return A;
}

template <class Fn>
double medianMs(int repeats, Fn&& fn) {
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
  return t[t.size() / 2];
}
}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::atoi(argv[1]) : 200, m = 100, wbar = 400, ms = 250;
  std::mt19937 gen(7);
  gphr::DenseMatrix PtU = randomMatrix(m, m, gen), PtF = randomMatrix(m, wbar, gen), StU = randomMatrix(ms, m, gen),
                    StF = randomMatrix(ms, wbar, gen);
  for (int i = 0; i < m; ++i) PtU(i, i) += 4.0;
  gphr::AdeimUpdateOptions opt;
  gphr::CoefficientFactor cf;
  const double tFactor = medianMs(repeats, [&] { cf = gphr::factorCoefficients(PtU, PtF, opt.coefficientTol); });
  gphr::AdeimUpdate up;
  const double tUpdate = medianMs(repeats, [&] { up = gphr::computeAdeimUpdate(cf, StU, StF, opt); });
  opt.rank = 50;
  const double tFixed = medianMs(repeats, [&] { gphr::computeAdeimUpdate(cf, StU, StF, opt); });
  std::printf("m %d wbar %d m_s %d (one rank): factorCoefficients %.3f ms, computeAdeimUpdate %.3f ms (r = %d of r_C = %d), "
              "with fixed r = 50 %.3f ms\n", m, wbar, ms, tFactor, tUpdate, up.rank, cf.rank(), tFixed);
  // The machine's DGEMM at the largest product of the update, S^T U (m_s x m) times C (m x wbar).
  gphr::DenseMatrix X(ms, wbar);
  const gphr::DenseMatrix& C = cf.C;
  const double tGemm = medianMs(repeats, [&] {
    Teuchos::BLAS<int, double>().GEMM(Teuchos::NO_TRANS, Teuchos::NO_TRANS, ms, wbar, m, 1.0, StU.values(), StU.stride(),
                                      C.values(), C.stride(), 0.0, X.values(), X.stride());
  });
  const double M = m, W = wbar, S = ms, gemmRate = 2.0 * S * M * W / (tGemm * 1e6);  // GFlop/s
  // factorCoefficients: GETRF + GETRI + (P^T U)^{-1} P^T F + GEQP3 of C^T (W x M) + TRTRI + Q by ORMQR.
  const double fFactor = 2.0 / 3 * M * M * M + 4.0 / 3 * M * M * M + 2 * M * M * W + (2 * W * M * M - 2.0 / 3 * M * M * M) +
                         M * M * M / 3 + (4 * W * M * M - 2 * M * M * M);
  const double bFactor = 8.0 * (M * M + M * W + M * W + 2 * M * M + W * M);  // P^T U, P^T F in; C, T, T^+, Q out
  // computeAdeimUpdate: X = S^T U C, X Q, the R factor of M (S x M), Z = R T, singular values of R and Z.
  const double fUpdate = 2 * S * M * W + 2 * S * W * M + (2 * S * M * M - 2.0 / 3 * M * M * M) + 2 * M * M * M +
                         2 * (8.0 / 3) * M * M * M;
  const double bUpdate = 8.0 * (S * M + S * W + M * W + W * M + 2 * M * M + S * M + M * M);  // in; a, b out
  const auto roofline = [&](const char* name, double flops, double bytes, double ms) {
    const double rate = flops / (ms * 1e6);
    std::printf("  %-19s %5.1f MFlop, %4.2f MB in+out, %4.1f flop/B, %5.1f GFlop/s = %3.0f %% of DGEMM\n", name,
                flops / 1e6, bytes / 1e6, flops / bytes, rate, 100.0 * rate / gemmRate);
  };
  std::printf("roofline (DGEMM %d x %d x %d: %.1f GFlop/s)%s\n", ms, m, wbar, gemmRate,
              up.rank == cf.rank() && cf.rank() == m ? "" : " [r < r_C or r_C < m: the full-rank counts below are approximate]");
  roofline("factorCoefficients", fFactor, bFactor, tFactor);
  roofline("computeAdeimUpdate", fUpdate, bUpdate, tUpdate);
  // The memory roof: a copy of 64 MB (far beyond the caches), bytes read plus bytes written. With
  // the DGEMM rate above it places each stage of adeim_paper.sh's per-stage roofline.
  std::vector<double> src(std::size_t(1) << 23, 1.0), dst(src.size());
  const double tCopy = medianMs(std::max(3, repeats / 20), [&] { std::copy(src.begin(), src.end(), dst.begin()); });
  std::printf("memory bandwidth (copy of %zu MB): %.1f GB/s\n", src.size() * 8 >> 20,
              2.0 * 8.0 * static_cast<double>(src.size()) / (tCopy * 1e6));
}
