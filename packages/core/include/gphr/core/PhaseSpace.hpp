#pragma once
/// @file
/// The phase space R^{2n} of y = (q, p) as a Tpetra map, and the canonical Poisson tensor
/// J_{2n} = [[0, I], [-I, 0]] (paper eq:full_model) applied without forming it.
///
/// Layout: global ids 0..n-1 are q, n..2n-1 are p. Each rank owns a block [a, b) of the n
/// degrees of freedom *for both components*, stored locally as q_a..q_{b-1}, p_a..p_{b-1}; so q_i
/// and its partner p_i always live on the same rank and J is a local permutation with signs.
#include <utility>

#include "gphr/core/Types.hpp"

namespace gphr {

/// The phase space R^{2n} of y = (q, p) and its Poisson tensor J_{2n} (see the file's description).
class PhaseSpace {
 public:
  /// n degrees of freedom per component, split as evenly as Tpetra splits n over the ranks.
  PhaseSpace(GO n, const RCP<const Comm>& comm);

  GO n() const { return n_; }  ///< n, the degrees of freedom per component.
  GO fullDim() const { return 2 * n_; }  ///< 2n, the size of the state y.
  LO numLocalDofs() const { return nLocal_; }  ///< Number of degrees of freedom this rank owns (per component).
  /// First degree of freedom this rank owns (global id of its first q entry).
  GO firstLocalDof() const { return first_; }
  /// State map (2n entries) and the map of the n degrees of freedom (e.g.\ grid points).
  const RCP<const Map>& map() const { return map_; }
  const RCP<const Map>& dofMap() const { return dofMap_; }  ///< Map of the n degrees of freedom.
  RCP<const Comm> comm() const { return map_->getComm(); }  ///< The communicator of the state map.

  /// out = J x, out = J^T x. x and out are vectors on map(); out must not alias x.
  void applyJ(const MultiVector& x, MultiVector& out) const;
  /// out = J^T x (x and out on map(); out must not alias x).
  void applyJT(const MultiVector& x, MultiVector& out) const;
  /// Row r of a matrix H appears in J H as row jRow(r).first times jRow(r).second:
  /// (J H)_{i,:} = H_{n+i,:} for q rows i < n and (J H)_{n+i,:} = -H_{i,:}.
  std::pair<GO, Scalar> jRow(GO r) const { return r < n_ ? std::pair<GO, Scalar>(r + n_, -1.0) : std::pair<GO, Scalar>(r - n_, 1.0); }

 private:
  GO n_;
  LO nLocal_;
  GO first_;
  RCP<const Map> map_, dofMap_;
};

}  // namespace gphr
