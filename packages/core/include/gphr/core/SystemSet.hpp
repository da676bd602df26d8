#pragma once
/// @file
/// The training systems of the offline stages that read snapshots in reduced coordinates (the DEIM
/// basis, the empirical quadrature, the gradient-DEIM basis): one HamiltonianSystem per training
/// parameter, as SnapshotSet holds one snapshot block per parameter. Given a factory, a system is
/// instantiated when it is asked for and only two are alive at a time: the first (its maps and
/// phase space stay valid for the set's lifetime) and the one asked for last. Each holds operators of
/// the full size (the SWE 128^2: ~8 MB per rank), so P of them at once grew the DEIM stage's memory
/// with the training set: 483 MB on 4 x 4 training against 384 MB on 2 x 2 (SWE 128^2, 1 rank).
/// Asking for a system is collective when the factory is (a scene's instance is).
#include <functional>
#include <initializer_list>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "gphr/core/HamiltonianSystem.hpp"

namespace gphr {

/// The systems of the training parameters, held or made on demand (see the file's description).
class SystemSet {
 public:
  /// Makes system j (collective when instantiation is).
  using Factory = std::function<RCP<const HamiltonianSystem>(size_t j)>;
  SystemSet() = default;
  /// Systems held in memory.
  SystemSet(std::vector<RCP<const HamiltonianSystem>> all) : all_(std::move(all)) {}  // NOLINT: a vector is a set
  /// Systems held in memory (a braced list).
  SystemSet(std::initializer_list<RCP<const HamiltonianSystem>> all) : all_(all) {}
  /// `count` systems made on demand by `make`.
  SystemSet(size_t count, Factory make) : count_(count), make_(std::move(make)) {}
  size_t size() const { return make_ ? count_ : all_.size(); }  ///< The number of systems.
  bool empty() const { return size() == 0; }                    ///< Whether there is none.
  /// System j. Made on demand, the reference stays valid until another j > 0 is asked for; system
  /// 0's for the set's lifetime.
  const RCP<const HamiltonianSystem>& operator[](size_t j) const {
    if (!make_) return all_.at(j);
    if (j >= count_) throw std::out_of_range("SystemSet: system index out of range");
    if (j == 0) {
      if (first_.is_null()) first_ = make_(0);
      return first_;
    }
    if (j != lastIndex_) {
      last_ = Teuchos::null;  // released before the next is made: two alive at most
      last_ = make_(j);
      lastIndex_ = j;
    }
    return last_;
  }

 private:
  std::vector<RCP<const HamiltonianSystem>> all_;
  size_t count_ = 0;
  Factory make_;
  mutable RCP<const HamiltonianSystem> first_, last_;
  mutable size_t lastIndex_ = std::numeric_limits<size_t>::max();
};

}  // namespace gphr
