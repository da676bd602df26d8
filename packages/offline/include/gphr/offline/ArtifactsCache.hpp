#pragma once
/// @file
/// The offline stages' cache: one HDF5 file (DIR/artifacts.h5 of `gphr run` and `gphr build`)
/// that holds the training snapshots, the basis, the DEIM bases and the term-weight fits, each a
/// keyed dataset. A dataset is reused only when its `config` attribute equals the key of what
/// would be computed now (the configuration text it depends on) and it carries the `complete`
/// mark, written last: a run killed while writing leaves a dataset without the mark, redone by
/// the next run. A file of another scene or state size is refused, naming the file.
#include <memory>
#include <string>
#include <vector>

#include "gphr/core/Types.hpp"
#include "gphr/io/Hdf5File.hpp"

namespace gphr {

/// The artifacts file of one scene and state size (see the file's description).
class ArtifactsCache {
 public:
  /// Opens the file at `path` or creates it with the scene's name and the state size 2n; creating
  /// it removes the checkpoint files left beside it (PodCheckpoint: PODs of the snapshots of a file
  /// that is gone). An existing file of another scene or size is an InputError naming the file.
  /// Rank 0 decides whether the file exists. Collective over `comm`.
  ArtifactsCache(std::string path, RCP<const Comm> comm, const std::string& sceneName, long fullDim);
  const std::string& path() const { return path_; }       ///< The file's path.
  const RCP<const Comm>& comm() const { return comm_; }   ///< The ranks that open it.
  /// The file opened for reading and writing (closed when the pointer goes): stages open it per
  /// dataset, so that a kill between two datasets leaves the finished ones intact. Collective.
  std::unique_ptr<Hdf5File> open() const;
  /// Whether `name` is complete and was computed from `key`.
  static bool holds(const Hdf5File& file, const std::string& name, const std::string& key);
  /// Marks `name` complete for `key`, after its data and attributes: the key, then the mark. Its
  /// data were handed to the file system before (a collective write returns when they are), so a
  /// killed process leaves marks only on complete data. With syncToDisk() the file is first flushed
  /// to the disk (H5Fflush: MPI_File_sync), so that a machine crash cannot keep a mark whose data
  /// the disk lacks; without it such a crash's damage is found where the data are read (their
  /// fingerprints, HDF5's metadata checksums), and the disk writes are started, not waited for
  /// (Hdf5File::startWriteback). Collective.
  void seal(Hdf5File& file, const std::string& name, const std::string& key) const;
  /// The same for several datasets (one flush for a round of the training, where syncToDisk()).
  void seal(Hdf5File& file, const std::vector<std::string>& names, const std::string& key) const;
  /// Stores `fingerprint`, columnFingerprint() of `name`'s columns (ColumnFingerprint.hpp), as its
  /// attribute: the cache's distributed data (snapshots, bases, checkpoints) carry it where a
  /// checksum would need them gathered. Written before seal(). Collective.
  static void stampFingerprint(Hdf5File& file, const std::string& name, const std::vector<double>& fingerprint);
  /// "" if X, read from `name` as its columns (first + i) every, i = 0, 1, ..., matches the stored
  /// fingerprint; else what is wrong ("column 17 (of the stored) does not match its fingerprint",
  /// "has no fingerprint"). Collective over X's ranks.
  static std::string fingerprintProblem(const Hdf5File& file, const std::string& name, const MultiVector& X,
                                        size_t every = 1, size_t first = 0);
  /// Removes `name` and creates its parent groups if missing: the dataset can be written anew.
  static void clear(Hdf5File& file, const std::string& name);
  /// Seconds of a stage's work between two checkpoints of its streaming POD (PodCheckpoint; 0:
  /// after every block). A kill loses at most about this much of a stage's work.
  double checkpointSeconds() const { return checkpointSeconds_; }
  /// Sets checkpointSeconds() (>= 0; an InputError naming the value otherwise).
  void setCheckpointSeconds(double seconds);
  /// Whether seal() flushes the file to the disk first (key output.syncArtifacts; default off: the
  /// flush is the time of writing the bytes to the disk, SWE 256^2's training 0.59 s of 37 s on the
  /// 2-core VM's 2 ranks, on every run, for a crash of the machine, not of gphr).
  bool syncToDisk() const { return syncToDisk_; }
  void setSyncToDisk(bool sync) { syncToDisk_ = sync; }  ///< Sets syncToDisk().

 private:
  std::string path_;
  RCP<const Comm> comm_;
  double checkpointSeconds_ = 60.0;
  bool syncToDisk_ = false;
};

}  // namespace gphr
