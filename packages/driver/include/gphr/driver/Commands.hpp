#pragma once
/// @file
/// The `gphr` commands besides `run`: build (offline stages -> a reduced-model file), query (the
/// file's models at many parameters, spread over the ranks) and validate (the models against the
/// full model over a set of test parameters). Each returns the process exit code; bad input is an
/// InputError (exit 2), thrown on every rank.
#include <fstream>
#include <functional>
#include <string>

#include "gphr/driver/RunContext.hpp"

#include "gphr/core/Provenance.hpp"

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

/// Collective: `error` is rank 0's (empty: none); every rank throws it as an InputError, so a
/// failure of rank 0's work (its report, its files) ends all ranks with one message.
void agreeOnError(const RCP<const Comm>& comm, std::string error);

/// Collective: rank 0 runs `work` (its report, its files); an InputError from it, prefixed with
/// `what`, ends every rank (agreeOnError).
void onRootAgreed(const RCP<const Comm>& comm, const std::string& what, const std::function<void()>& work);

/// `gphr build`: the offline stages of the config at `configPath` -> the reduced-model file `modelPath`.
int runBuild(const std::string& configPath, const std::string& modelPath, const std::string& artifactsDir,
             const RCP<const Comm>& comm);
/// `gphr query`: the model file's models at the parameters of `queriesPath`, results in `outputDir`;
/// each rank's queries on `threads` threads (0: defaultQueryThreads, QueryThreads.hpp).
int runQuery(const std::string& modelPath, const std::string& queriesPath, const std::string& outputDir,
             const RCP<const Comm>& comm, int threads = 0);

/// `gphr validate`: the model file's models against the full model at the test parameters of `testsPath`.
int runValidate(const std::string& modelPath, const std::string& testsPath, const std::string& outputDir,
                const RCP<const Comm>& comm);


}  // namespace gphr
