#pragma once
/// @file
/// One gphr command per output directory: an advisory lock, DIR/.gphr.lock, held for the life of
/// the command. Rank 0 takes it with flock (the kernel releases it when the process ends, kill -9
/// included, so a killed run never leaves a stale lock) and writes its owner into it (pid, host,
/// command, start time). A second gphr on the same directory ends on every rank with an InputError
/// (exit 2) that names the first. The file is removed when the command ends.
#include <string>

#include "gphr/core/Types.hpp"

namespace gphr {

/// The lock of one output directory (see the file's description). Collective.
class OutputLock {
 public:
  /// Takes the lock of `dir` (which exists) for `command`; InputError on every rank naming the owner
  /// if another process holds it, or naming the file if it cannot be made.
  OutputLock(const std::string& dir, const std::string& command, const RCP<const Comm>& comm);
  ~OutputLock();  ///< Releases the lock and removes the file (rank 0).
  OutputLock(const OutputLock&) = delete;             ///< Not copyable.
  OutputLock& operator=(const OutputLock&) = delete;  ///< Not copyable.

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace gphr
