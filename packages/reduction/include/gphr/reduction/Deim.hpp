#pragma once
/// @file
/// Discrete empirical interpolation on a distributed DEIM basis U (d x m, on the row map of G):
/// interpolation indices P and the weights the hyper-reduced model needs (paper eq:DEIMproj,
/// eq:hhr_and_gradhhr):  N_hr = v^T U (P^T U)^{-1} P^T G,  so the m numbers
///   deimWeights = (U^T P)^{-1} U^T v      (the nonzeros of w = P (U^T P)^{-1} U^T v)
/// are all that is kept of U online.
#include <string>
#include <utility>
#include <vector>

#include "gphr/core/Types.hpp"

namespace gphr {

/// Greedy DEIM (Chaturantabut & Sorensen 2010, Alg.\ 1): index l is the global argmax of the
/// interpolation residual of column l (ties: the smallest global id, so every rank count agrees).
/// QDEIM (Drmac & Gugercin 2016): the first m pivots of a column-pivoted QR (LAPACK GEQP3) of U^T;
/// U is gathered on every rank for it (d x m numbers; fine at the paper's sizes, greedy DEIM
/// stays distributed). method: "deim" | "qdeim". Collective; InputError if U is rank-deficient
/// at the sampled rows (the greedy residual vanishes) or m exceeds U's columns.
std::vector<GO> selectDeimIndices(const MultiVector& U, int m, const std::string& method = "deim");

/// The partial point update of ADEIM (Peherstorfer & Willcox 2015, Sec.\ 4.1; the paper's
/// "update only the indices associated with the DEIM basis vectors that have undergone the largest
/// rotations"): for each column i in `columns`, in order, index i of P is chosen again as the
/// greedy DEIM step would for column i with the other m - 1 columns and indices fixed, the global
/// argmax of |u_i - U_{-i} (P_{-i}^T U_{-i})^{-1} P_{-i}^T u_i| over the rows outside P_{-i}. Costs
/// O(d m) and two collectives per column instead of greedy DEIM's O(d m^2). Returns the new P;
/// InputError if that residual vanishes (u_i depends on the other columns at P_{-i}).
std::vector<GO> replaceDeimIndices(const MultiVector& U, std::vector<GO> P, const std::vector<int>& columns);

/// Global argmax of |x_l| over this rank's rows l of `map` not in `exclude` (ties: the smallest
/// gid, so every rank count agrees); returns (gid, |x|), gid -1 if no row qualifies. One gatherAll.
/// The greedy selections over distributed rows (DEIM's point update, the empirical quadrature's terms).
std::pair<GO, double> globalArgmaxAbs(const Map& map, const std::vector<double>& x, const std::vector<char>& exclude);

/// DEIM weights (U^T P)^{-1} U^T v of indices P, with cond(P^T U) and P^T U.
struct DeimWeights {
  std::vector<double> weights;    ///< (U^T P)^{-1} U^T v, one per index
  double conditionNumber = 0.0;   ///< cond_2(P^T U), or its 1-norm estimate: the DEIM error amplification
  std::vector<double> pointRows;  ///< P^T U as gathered (m x m, column-major): reusable while U and P stay
};
/// cond_2(P^T U) of U's first indices.size() columns (LAPACK SVD of the m x m matrix). Collective.
double deimConditionNumber(const MultiVector& U, const std::vector<GO>& indices);
/// U's first indices.size() columns. Collective. estimateCondition: conditionNumber is LAPACK
/// GECON's estimate of cond_1(P^T U) from the LU the weights need (O(m^2); 0.1 ms against the
/// SVD's 0.9 ms at m = 100), for GP-ADEIM, which reports it at every update; otherwise the exact
/// cond_2 (one SVD).
DeimWeights computeDeimWeights(const MultiVector& U, const std::vector<GO>& indices, const Vector& v,
                               bool estimateCondition = false);

}  // namespace gphr
