#pragma once
/// @file
/// The output directory of the commands: creating it, writing its text files whole or not at all,
/// and one rule for rank 0's work there (rank 0 acts, every rank agrees on its error).
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "gphr/driver/RunContext.hpp"

namespace gphr {

/// Creates ctx.outputDir (rank 0) and, if removeSummary, removes an earlier run's summary.json
/// (then ctx.replacesEarlierRun). Collective: a failure on rank 0 is thrown on every rank.
void prepareOutputDir(RunContext& ctx, bool removeSummary);

/// Creates `dir` on rank 0; collective like prepareOutputDir.
void makeDirectory(const std::string& dir, const RCP<const Comm>& comm);

/// Writes `text` to `path` through `path`.tmp and a rename, so that the file appears whole or not
/// at all; InputError naming the path and the system's reason (a full disk, a read-only or missing
/// directory) if any step fails. On the calling rank alone.
void writeTextFile(const std::string& path, const std::string& text);

/// Ends writing the text file `path` through `os`: flushes and closes it; InputError naming the path
/// and the system's reason if it could not be opened or a write failed (a full disk).
void finishText(std::ofstream& os, const std::string& path);

/// A path a command reads or writes, and what the messages call it ("the queries file", "--output").
struct NamedPath {
  std::string path;  ///< as given
  std::string what;  ///< its name in messages
};
/// Refuses, before any work (InputError on the calling rank), an output that is an input or a
/// directory that contains one: the paths resolved (absolute, '.' and '..' folded, symbolic links
/// of their existing part followed), so that no spelling or link lets a command overwrite its own
/// input (gphr query M.h5 Q.yaml --output DIR with DIR/results.h5 as M.h5, say).
void requireOutputsApart(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs);

/// Collective: rank 0 creates and removes a file beside `path` (in its directory, created if
/// missing), so that an output that cannot be written there (a read-only or missing directory,
/// no permission) is an InputError naming `what` before any work, not after it.
void requireWritableBeside(const std::string& path, const std::string& what, const RCP<const Comm>& comm);

/// Collective: `error` is rank 0's (empty: none); every rank throws it as an InputError, so a
/// failure of rank 0's work (its report, its files) ends all ranks with one message.
void agreeOnError(const RCP<const Comm>& comm, std::string error);

/// Collective: rank 0 runs `work` (its report, its files); an InputError from it, prefixed with
/// `what`, ends every rank (agreeOnError).
void onRootAgreed(const RCP<const Comm>& comm, const std::string& what, const std::function<void()>& work);

}  // namespace gphr
