#pragma once
/// @file
/// The sampling rows S of GP-ADEIM (paper Sec.\ 4.2, alg:indices_adapt, fig:schro_samplingstrats):
/// which m_s rows of the residual R_j = U_j C_j - F_j the rank-r update fits. Rules:
///   projected  the rows of R_j C_bar_j of largest norm (alg:indices_adapt; Theorem
///              theo:rhoj_squared: they minimize the bound on the distance to span F_j)
///   residual   the rows of R_j of largest norm (Peherstorfer 2020, Alg. 1)
///   random     m_s rows drawn uniformly (seeded: the same rows on every rank count)
/// Scores are computed per owned row of G, in parallel over the MPI ranks; only each rank's
/// m_s best candidates are exchanged, never d-sized data.
#include <string>
#include <vector>

#include "gphr/core/DenseTypes.hpp"
#include "gphr/core/Types.hpp"
#include "gphr/hyper/AdeimUpdate.hpp"

namespace gphr {

/// Per local row i: ||(U_i C - F_i) Q_1|| (projected rule; Q_1 = cf.Q, C's row-space basis) or
/// ||U_i C - F_i|| (residual rule), C = cf.C. U: local rows x m, column-major with leading dimension
/// ldU (a MultiVector's local view, read in place); Fl: local rows x wbar, row-major.
std::vector<double> residualRowNorms(const double* U, int ldU, const std::vector<double>& Fl, int rows,
                                     const CoefficientFactor& cf, bool projected);

/// How many sampling rows (m_s) to take: a fixed count, or by the relative score tolerance tau_s.
struct SampleCount {
  int fixed = 0;           ///< m_s > 0: exactly this many (fewer if the rows run out)
  double relTol = 0.0;     ///< fixed == 0: rows with score > relTol * (largest score), the paper's tau_s
  int atLeast = 1;         ///< ... but at least this many (m)
  int atMost = 0;          ///< ... and at most this many
};

/// The rows (global ids, ascending) with the largest scores over all ranks, excluding `exclude`
/// (the interpolation rows, where R_j vanishes). Ties: the smallest gid. Collective.
std::vector<GO> largestScoreRows(const Map& rowMap, const std::vector<double>& scores, const std::vector<GO>& exclude,
                                 const SampleCount& count);

/// count.fixed (or count.atLeast) rows drawn uniformly from the contiguous global rows of rowMap
/// without `exclude`, from a generator seeded by (seed, draw): replicated, the same on every rank.
std::vector<GO> randomRows(const Map& rowMap, const std::vector<GO>& exclude, int count, unsigned long long seed,
                           long draw);

}  // namespace gphr
