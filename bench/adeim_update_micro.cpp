// Micro-benchmark of one GP-ADEIM update's dense algebra at the paper's NLS size (m = 100,
// wbar = 2k w = 400, m_s = 250, one rank): factorCoefficients (C_j and its rank-revealing factor)
// and computeAdeimUpdate (the rank-r update, r by tau_r = 1e-12), on random data. Wall time per
// call, the median of repeated calls (run it with OPENBLAS_NUM_THREADS=1 for the benchmark's
// setting), printed side by side.
// usage: adeim_update_micro [REPEATS]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

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
}
