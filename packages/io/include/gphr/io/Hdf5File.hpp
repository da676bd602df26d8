#pragma once
// Parallel HDF5 artifacts (HDF5 1.10 with MPI-IO). States are stored as datasets of shape
// (count, 2n) in global-id order (q then p); each rank writes and reads only its own entries
// with one collective call. Replicated data (histories, attributes) is written by rank 0.
// Every call is collective over the file's communicator.
#include <hdf5.h>

#include <functional>
#include <string>
#include <vector>

#include "gphr/core/PhaseSpace.hpp"

namespace gphr {

class Hdf5File {
 public:
  enum class Mode { Create, ReadOnly, ReadWrite };
  Hdf5File(const std::string& path, const RCP<const Comm>& comm, Mode mode);
  ~Hdf5File();
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;
  void close();

  const std::string& path() const { return path_; }
  bool exists(const std::string& name) const;  // a dataset or group at this path
  void createGroup(const std::string& name);
  // Unlink a dataset or group (no-op if absent); the space is not reclaimed (HDF5 1.10).
  void remove(const std::string& name);
  bool hasAttribute(const std::string& object, const std::string& key) const;
  void flush();

  // States: columns of `states` (vectors on space.map()) as rows of dataset `name`.
  void writeStates(const std::string& name, const MultiVector& states, const PhaseSpace& space);
  RCP<MultiVector> readStates(const std::string& name, const PhaseSpace& space) const;
  // Columns of a MultiVector on a contiguous map (e.g. the DEIM basis on the rows of G) as rows
  // of dataset `name` (shape (cols, global length)), each rank its own hyperslab.
  void writeColumns(const std::string& name, const MultiVector& X);
  RCP<MultiVector> readColumns(const std::string& name, const RCP<const Map>& map) const;
  // Replicated 1-D / 2-D double data (e.g. histories), written by rank 0, read by all.
  void writeArray(const std::string& name, const std::vector<double>& data, size_t rows, size_t cols);
  std::vector<double> readArray(const std::string& name, size_t* rows = nullptr, size_t* cols = nullptr) const;

  void setAttribute(const std::string& object, const std::string& key, const std::string& value);
  void setAttribute(const std::string& object, const std::string& key, const std::vector<double>& value);
  std::string stringAttribute(const std::string& object, const std::string& key) const;
  std::vector<double> doubleAttribute(const std::string& object, const std::string& key) const;

 private:
  using Selector = std::function<void(hid_t, hsize_t)>;
  void writeDistributed(const std::string& name, const MultiVector& X, hsize_t N, const Selector& select);
  RCP<MultiVector> readDistributed(const std::string& name, const RCP<const Map>& map, hsize_t N,
                                   const Selector& select, const char* what) const;
  hid_t openDataset(const std::string& name) const;
  std::string path_;
  RCP<const Comm> comm_;
  hid_t file_ = -1;
};

// Write-then-rename: the final name appears only when the file is complete. A RenameOnCommit
// that goes out of scope uncommitted removes its temporary file (rank 0).
class RenameOnCommit {
 public:
  RenameOnCommit(std::string finalPath, RCP<const Comm> comm);
  ~RenameOnCommit();
  const std::string& tempPath() const { return temp_; }
  const std::string& finalPath() const { return final_; }
  void commit();  // collective: barrier, then rank 0 renames

 private:
  std::string final_, temp_;
  RCP<const Comm> comm_;
  bool done_ = false;
};

}  // namespace gphr
