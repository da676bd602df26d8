#pragma once
/// @file
/// The DEIM basis of GP-DEIM (paper sec:ConstrDEIM): POD of the reduced-Jacobian snapshots
///   M_J = [ J_G(y0_j + A A^T y_s) A ]   (eq:snaps_JG, shifted: y_s = y - y0_j),
/// d x 2k per kept training state, streamed into an incremental SVD (StreamingPod) or a
/// randomized range finder, so that M_J (d x 2k x states: 5 GB at the paper's NLS sizes) is never held.
#include <Teuchos_ParameterList.hpp>
#include <string>
#include <vector>

#include "gphr/core/HamiltonianSystem.hpp"
#include "gphr/core/SnapshotSet.hpp"

namespace gphr {

/// Options of the DEIM basis: its rank, the snapshots used, and the SVD (exact streaming POD or randomized).
struct DeimBasisOptions {
  int maxRank = 0;        ///< singular triplets kept between blocks (>= the largest m wanted); 0: min(d, 400)
  int snapshotEvery = 1;  ///< use every N-th stored training state (the paper: 20)
  int blockSnapshots = 0; ///< reduced-Jacobian snapshots (2k columns each) per POD step; 0: ~maxRank columns
  /// exact: the streaming POD (incremental TSQR + SVD); randomized: the range finder of HMT11
  /// (one streamed pass + powerIterations passes + one for B B^T), oversampling extra columns.
  std::string svd = "exact";
  std::string podRoute = "auto";  ///< exact: the StreamingPod's step route (auto | tsqr | replicated)
  int oversampling = 10;  ///< randomized: extra columns of the range finder.
  int powerIterations = 1;  ///< randomized: power iterations (passes over the snapshots).
  /// randomized, its last pass (B = Q^T M_J): true, by the Gram matrix B B^T (one small GEMM per
  /// snapshot; resolves sigma down to ~1e-7 sigma_1, enough for the DEIM sizes worth using);
  /// false, by a blocked QR of the stacked B^T (~eps sigma_1; a few times the Gram's cost), for a
  /// basis that must keep directions far down the spectrum (GP-ADEIM's initial U_0: m of them).
  bool gramProjection = true;
  unsigned long long seed = 20231122;  ///< randomized: seed of the Gaussian test matrix.
};

/// The options of a `hyper` configuration section (validated: every key present); largestM: the
/// largest DEIM size wanted (maxRank 0 keeps largestM + 32 triplets).
DeimBasisOptions deimBasisOptionsFrom(const Teuchos::ParameterList& hyper, int largestM);

constexpr int kDefaultDeimRank = 400;  ///< Default largest m (singular triplets kept) of the DEIM basis.

/// The DEIM basis U (d x rank) of GP-DEIM with the singular values and snapshot statistics of its POD.
struct DeimBasis {
  RCP<MultiVector> U;                  ///< d x rank, on the row map of G
  std::vector<double> singularValues;  ///< of M_J (the leading ones kept)
  long snapshots = 0;                  ///< reduced-Jacobian snapshots (states) used
  double energy = 0.0;                 ///< ||M_J||_F^2
  /// svd exact: the streaming POD's steps by route (hyper.podRoute); all 0 for randomized
  /// @{
  int tsqrSteps = 0, stackedSteps = 0, replicatedSteps = 0, treeSteps = 0;
  /// @}
};

/// systems[j]: the (shifted) system at training parameter j; states[j]: its stored states in the
/// system's own coordinates. A: the reduced basis (2n x 2k). Collective.
DeimBasis computeDeimBasis(const std::vector<RCP<const HamiltonianSystem>>& systems,
                           const SnapshotSet& states, const MultiVector& A,
                           const DeimBasisOptions& options);

}  // namespace gphr
