#pragma once
/// @file
/// Checkpoints of a long streaming POD in the artifacts file, so that a stage killed mid-way (a
/// job's time limit, say) goes on from where it stood: the basis stage after each training
/// parameter's block, the DEIM basis stage after each round of chunks. A checkpoint is the POD's
/// state (StreamingPod::State: U, sigma, energy, columns, steps), how far the stage got
/// (`progress`: blocks or chunks done) and the stage's own figures, sealed like any dataset
/// (ArtifactsCache). They go to a file of their own beside the artifacts file (ARTIFACTS.ckpt_NAME,
/// removed when the stage's result is written): HDF5 1.10 does not reclaim a removed dataset's
/// space, so slots rewritten in artifacts.h5 would leave it larger by two checkpoints per stage.
/// Two slots are written in turn, so that a kill while one is written leaves the other (one that
/// damages the file's HDF5 metadata leaves it unreadable: no checkpoint, the stage starts afresh);
/// a restart takes the complete one that got furthest. A new artifacts file removes them
/// (ArtifactsCache). Written at most every ArtifactsCache::checkpointSeconds()
/// of the stage's work (default 60): each costs a write of the POD's U (151 MB at SWE 256^2).
#include <Teuchos_Time.hpp>
#include <string>
#include <vector>

#include "gphr/offline/ArtifactsCache.hpp"
#include "gphr/reduction/StreamingPod.hpp"

namespace gphr {

/// What a checkpoint holds besides the POD's state.
struct PodProgress {
  int progress = 0;            ///< blocks or chunks done (0: none)
  std::vector<double> extra;   ///< the stage's own figures (energy, statistics, seconds, ...)
};

/// The checkpoints of one stage's streaming POD (see the file's description).
class PodCheckpoint {
 public:
  /// Checkpoints of the dataset `name` (the stage's result) under `key` (what it is computed from,
  /// and how it is cut into blocks); none with a null cache. A POD on a contiguous map is stored
  /// as columns (Hdf5File::writeColumns); one on the state map of `space` as states.
  PodCheckpoint(const ArtifactsCache* cache, std::string name, std::string key, const PhaseSpace* space = nullptr);
  bool enabled() const { return cache_ != nullptr; }  ///< Whether there is a file to write to.
  /// Writes a checkpoint into the slot not written last, when the cache's checkpointSeconds() have
  /// passed since this object was made or last wrote (rank 0's clock decides for all); returns
  /// whether it wrote. Collective over the cache's ranks.
  bool write(const StreamingPod::State& pod, const PodProgress& at);
  /// The complete checkpoint that got furthest with progress below `limit` (the rows of its U on
  /// `map`) into `pod`, or progress 0 where there is none; `extraSize`: the figures expected. A
  /// file that cannot be read, or holds other figures, counts as none (said on stderr; the next
  /// write makes it anew). Collective.
  PodProgress read(const RCP<const Map>& map, size_t extraSize, int limit, StreamingPod::State& pod);
  void clear() const;  ///< Removes the checkpoint file (the result is written). Collective.
  std::string path() const;  ///< The checkpoint file's path.

 private:
  static std::string slot(int i) { return "/slot" + std::to_string(i); }
  bool exists() const;  // the file, as rank 0 sees it
  const ArtifactsCache* cache_;
  std::string name_, key_;
  const PhaseSpace* space_;
  Teuchos::Time sinceWrite_{"checkpoint"};  // since made or last written
  int next_ = 0;             // the slot the next write goes to
  bool unreadable_ = false;  // the file was found unreadable: the next write creates it anew
};

}  // namespace gphr
