#pragma once
/// @file
/// Rank groups of the offline stages: the world communicator split into groups of consecutive
/// ranks (the last group takes the remainder), each working on its own share of a stage's items
/// (training parameters, chunks of snapshots) side by side, on a distributed object of its own.
/// Besides the split, the two moves between a world-distributed object and a group's copy of it:
///   toGroup:  every group gets the whole of a world MultiVector, in its own row distribution;
///   toWorld:  one group's MultiVector, in the world's distribution (the others send nothing: what
///             moves is that group's columns alone, whatever the number of groups).
/// (A group's training snapshots need no move: its ranks write them to the artifacts file
/// themselves, Hdf5File::writeStateRows.)
/// Each is one Tpetra Import/Export between the world map and a group map's rows seen from the
/// world communicator (toGroup: a map that holds every row once per group; toWorld: the rows of
/// the sending group only).
#include <string>

#include "gphr/core/Error.hpp"
#include "gphr/core/Types.hpp"

namespace gphr {

/// The split of `world` into groups of `size` consecutive ranks (see the file's description).
class RankGroups {
 public:
  /// size in [1, world size]; groups = world size / size, the last one larger by the remainder.
  RankGroups(RCP<const Comm> world, int size);
  int count() const { return count_; }  ///< The number of groups.
  int group() const { return group_; }  ///< This rank's group, 0 .. count() - 1.
  int size() const { return size_; }    ///< The ranks per group asked for (the last group may hold more).
  bool leader() const { return sub_->getRank() == 0; }  ///< Whether this rank is its group's first.
  const RCP<const Comm>& world() const { return world_; }  ///< The whole communicator.
  const RCP<const Comm>& sub() const { return sub_; }      ///< This rank's group's communicator.

  /// X (on a map of world()) as a MultiVector on groupMap (a map of sub() over the same global
  /// ids): every group receives all of X. Collective over world().
  RCP<MultiVector> toGroup(const MultiVector& X, const RCP<const Map>& groupMap) const;
  /// The move of group `owner`'s MultiVectors on groupMap (a map of sub()) to worldMap (a map of
  /// world() over the same global ids): an Export from the rows the owner's ranks hold, none on the
  /// other groups' ranks. Made once, used for each MultiVector the group sends. Collective over world().
  RCP<const Export> fromGroup(int owner, const Map& groupMap, const RCP<const Map>& worldMap) const;
  /// Group `owner`'s Xg (`columns` columns on its groupMap; null on the other groups' ranks) on the
  /// world map, through `move` = fromGroup(owner, ...). Collective over world().
  RCP<MultiVector> toWorld(const MultiVector* Xg, const Export& move, size_t columns) const;

 private:
  RCP<const Map> groupRowsOnWorld(const Map& groupMap) const;
  RCP<const Comm> world_, sub_;
  int size_, count_, group_;
};

/// What kind of error a failure is, so that every rank throws the kind the failing rank caught.
enum class FailureKind { Solver, Input, Internal };
/// Collective over `world`: returns when `failure` is empty on every rank, else throws, on every
/// rank, the failure text of the lowest rank that has one as the `kind` that rank gave (SolverError,
/// InputError, or std::runtime_error for Internal). Groups that work apart (training parameters,
/// validation points, DEIM chunks) call it before they meet again, so that no group waits at a
/// collective for one that failed.
void agreeOnFailure(const Comm& world, const std::string& failure, FailureKind kind = FailureKind::Solver);

/// A rank's failure in work done apart from the other groups, for agreeOnFailure: "" when none.
struct GroupFailure {
  std::string text;                        ///< what failed ("": nothing)
  FailureKind kind = FailureKind::Solver;  ///< the kind of error it was
};
/// Runs `work` and returns what it threw as a GroupFailure: "`what`: `solverWhat`message" for a
/// SolverError, "`what`: message" for an InputError (Input) or another std::exception (Internal);
/// without the "`what`: " where `what` is empty.
template <class Work>
GroupFailure failureOf(const std::string& what, const std::string& solverWhat, Work&& work) {
  const std::string head = what.empty() ? std::string() : what + ": ";
  try {
    work();
    return {};
  } catch (const SolverError& e) {
    return {head + solverWhat + e.what(), FailureKind::Solver};
  } catch (const InputError& e) {
    return {head + e.what(), FailureKind::Input};
  } catch (const std::exception& e) {
    return {head + e.what(), FailureKind::Internal};
  }
}
/// agreeOnFailure(world, failure.text, failure.kind).
inline void agreeOnFailure(const Comm& world, const GroupFailure& failure) {
  agreeOnFailure(world, failure.text, failure.kind);
}

}  // namespace gphr
