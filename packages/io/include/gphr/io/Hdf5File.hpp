#pragma once
/// @file
/// Parallel HDF5 artifacts (HDF5 1.10 with MPI-IO). States are stored as datasets of shape
/// (count, 2n) in global-id order (q then p); each rank writes and reads only its own entries
/// with one collective call. Replicated data (histories, attributes) is written by rank 0.
/// Every call is collective over the file's communicator.
#include <hdf5.h>

#include <functional>
#include <string>
#include <vector>

#include "gphr/core/PhaseSpace.hpp"

namespace gphr {

/// A parallel HDF5 file of GPHR's artifacts (see the file's description); every call is collective.
class Hdf5File {
 public:
  /// How the file is opened: created (truncating), read only, or read and written.
  enum class Mode { Create, ReadOnly, ReadWrite };
  /// Opens (or creates) the file at `path` on the ranks of `comm`.
  Hdf5File(const std::string& path, const RCP<const Comm>& comm, Mode mode);
  ~Hdf5File();
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;
  /// Closes the file (also done by the destructor). After a failed collective write of a file
  /// open on several ranks it does not call H5Fclose (and closeFailed() becomes true): the ranks'
  /// HDF5 states then differ (a full disk met by rank 0 alone, which writes the replicated
  /// datasets), and the collective close hung with each rank in another barrier.
  void close();
  /// Whether a file of this process could not be closed (H5Fclose failed: a full disk when HDF5
  /// wrote the file's last metadata, say). HDF5 1.10 then leaves the file half-closed in its table,
  /// and its own termination (at MPI_Finalize) crashes on it: a program that finds this true should
  /// end without finalizing MPI, as gphr's main does.
  static bool closeFailed();

  const std::string& path() const { return path_; }  ///< The file's path.
  bool exists(const std::string& name) const;  ///< a dataset or group at this path
  void createGroup(const std::string& name);  ///< Creates the group `name`.
  /// Unlink a dataset or group (no-op if absent); the space is not reclaimed (HDF5 1.10).
  void remove(const std::string& name);
  /// Whether `object` has the attribute `key`.
  bool hasAttribute(const std::string& object, const std::string& key) const;
  void flush();  ///< Flushes HDF5's buffers to the file and the file to the disk (MPI_File_sync).
  /// Asks the operating system to start writing the file's written bytes to the disk, without
  /// waiting for them (Linux: sync_file_range; elsewhere nothing): a later fsync, of this file or
  /// on ext4 of any file (its journal commit also writes this one's pending data), then finds them
  /// written. Not collective; each rank asks for its own node's pages. Best effort: no error.
  void startWriteback() const;

  /// States: columns of `states` (vectors on space.map()) as rows of dataset `name`.
  void writeStates(const std::string& name, const MultiVector& states, const PhaseSpace& space);
  /// The states written by writeStates(), distributed on space.map().
  RCP<MultiVector> readStates(const std::string& name, const PhaseSpace& space) const;
  /// Rows 0, every, 2 every, ... of a (count, 2n) dataset of states: ceil(count / every) columns.
  RCP<MultiVector> readStates(const std::string& name, const PhaseSpace& space, hsize_t every) const;
  static constexpr hsize_t kAllRows = static_cast<hsize_t>(-1);  ///< readStates' `columns`: all from `first` on.
  /// `columns` of those rows from the `first`-th on (rows first every, (first + 1) every, ...): a
  /// column block of the states, so that a reader holds a block, not the dataset. The range must lie
  /// within the ceil(count / every) rows (an InputError naming it otherwise).
  RCP<MultiVector> readStates(const std::string& name, const PhaseSpace& space, hsize_t every, hsize_t first,
                              hsize_t columns) const;
  /// Creates a (count, fullDim) dataset of states to be filled by writeStateRows (collective).
  void createStates(const std::string& name, hsize_t count, hsize_t fullDim);
  /// Rows first .. first + b - 1 of dataset `name` (createStates), written by one rank group
  /// (collective over the file's ranks): the b columns of `states` on the ranks of the group that
  /// integrated them (`groupSpace` its phase space, whose dofs are the world's, split over the
  /// group's ranks), null (both) on every other rank, which must still call; `b` the same on all
  /// ranks. The same rows as writeStates() of those states moved to all ranks.
  void writeStateRows(const std::string& name, hsize_t first, hsize_t b, const MultiVector* states,
                      const PhaseSpace* groupSpace);
  /// Columns of a MultiVector on a contiguous map (e.g.\ the DEIM basis on the rows of G) as rows
  /// of dataset `name` (shape (cols, global length)), each rank its own hyperslab.
  void writeColumns(const std::string& name, const MultiVector& X);
  /// The columns written by writeColumns(), distributed on `map`.
  RCP<MultiVector> readColumns(const std::string& name, const RCP<const Map>& map) const;
  /// Replicated 1-D / 2-D double data (e.g.\ histories), written by rank 0, read by all.
  void writeArray(const std::string& name, const std::vector<double>& data, size_t rows, size_t cols);
  /// The array written by writeArray(); its shape into rows and cols if given.
  std::vector<double> readArray(const std::string& name, size_t* rows = nullptr, size_t* cols = nullptr) const;

  /// Sets a string attribute of `object` (rank 0 writes).
  void setAttribute(const std::string& object, const std::string& key, const std::string& value);
  /// Sets a double-array attribute of `object` (rank 0 writes).
  void setAttribute(const std::string& object, const std::string& key, const std::vector<double>& value);
  /// A string attribute of `object`, read on every rank.
  std::string stringAttribute(const std::string& object, const std::string& key) const;
  /// A double-array attribute of `object`, read on every rank.
  std::vector<double> doubleAttribute(const std::string& object, const std::string& key) const;

 private:
  /// H5Lexists, its error (a damaged group) an InputError instead of "absent".
  bool linkExists(const std::string& name) const;
  /// Selects this rank's entries of `rows` rows first, first + every, ... of a file space.
  using Selector = std::function<void(hid_t space, hsize_t first, hsize_t every, hsize_t rows)>;
  /// A (count, N) dataset; this rank's entries the columns of X (none where X is null).
  void writeDistributed(const std::string& name, hsize_t count, hsize_t N, const MultiVector* X,
                        const Selector& select);
  /// Rows first, first + 1, ... (X's columns) of an existing dataset, this rank's entries (none where X is null);
  /// `width`, when not 0, the row length X's selection expects (an InputError where the dataset's differs).
  void writeRows(const std::string& name, hsize_t first, hsize_t rows, const MultiVector* X, const Selector& select,
                 hsize_t width = 0);
  /// Rows first every, (first + 1) every, ... (`columns` of them; all from `first` on if columns
  /// is kAllRows) of a (count, N) dataset, distributed on `map`.
  RCP<MultiVector> readDistributed(const std::string& name, const RCP<const Map>& map, hsize_t N,
                                   const Selector& select, const char* what, hsize_t every = 1, hsize_t first = 0,
                                   hsize_t columns = kAllRows) const;
  hid_t openDataset(const std::string& name) const;
  std::string path_;
  RCP<const Comm> comm_;
  hid_t file_ = -1;
  bool writeFailed_ = false;  ///< a collective write or flush failed (close() then skips H5Fclose on several ranks)
  /// checkOnAll of a collective write, remembering its failure for close().
  void checkWrite(herr_t status, const std::string& what);
};

/// Write-then-rename: the final name appears only when the file is complete. A RenameOnCommit
/// that goes out of scope uncommitted removes its temporary file (rank 0).
class RenameOnCommit {
 public:
  /// A temporary name next to `finalPath`, renamed on commit().
  RenameOnCommit(std::string finalPath, RCP<const Comm> comm);
  ~RenameOnCommit();
  const std::string& tempPath() const { return temp_; }  ///< The temporary path to write to.
  const std::string& finalPath() const { return final_; }  ///< The final path.
  void commit();  ///< collective: barrier, then rank 0 renames

 private:
  std::string final_, temp_;
  RCP<const Comm> comm_;
  bool done_ = false;
};

}  // namespace gphr
