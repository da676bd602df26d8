// The `gphr` command. Exit codes: 0 success, 2 bad input (one line on stderr naming the problem),
// 3 solver failure, 1 anything else.
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <Tpetra_Core.hpp>

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <thread>
#include <unistd.h>
#include <vector>

#include <Teuchos_Time.hpp>

#include <cmath>
#include <cstdlib>

#include "gphr/core/Error.hpp"
#include "gphr/core/Progress.hpp"
#include "gphr/driver/Commands.hpp"
#include "gphr/driver/Console.hpp"
#include "gphr/driver/Config.hpp"
#include "gphr/driver/OutputDirectory.hpp"
#include "gphr/driver/OutputLock.hpp"
#include "gphr/driver/QueryThreads.hpp"
#include "gphr/driver/HyperStage.hpp"
#include "gphr/driver/Report.hpp"
#include "gphr/driver/RomStage.hpp"
#include "gphr/io/Hdf5File.hpp"
#include "gphr/models/SceneFactory.hpp"
#include "gphr/core/Method.hpp"

namespace {

struct Args {
  enum Command { Run, Build, Query, Validate, Help } command = Run;
  enum Verbosity { Quiet, Normal, Verbose } verbosity = Normal;
  std::string config, output = "gphr-output", model, queries;
  int threads = 0;  // query: threads per rank, 0 = the default (QueryThreads.hpp)
  double targetError = 0.0;  // build: --target-error EPS (0: the config's build.targetError)
};

const char* kUsage = "usage: gphr [--output DIR] | run CONFIG [--output DIR] | build CONFIG --model FILE.h5 "
                     "[--output DIR] [--target-error EPS] | query MODEL.h5 QUERIES.yaml [--output DIR] [--threads N] | validate MODEL.h5 TESTS.yaml "
                     "[--output DIR] | --help; each command also takes --verbose or --quiet";

// --output DIR, --model FILE (build), --threads N (query), --verbose and --quiet after the
// positional arguments.
void options(Args& a, const std::vector<std::string>& v, size_t from, bool model, bool threads = false) {
  // The path after --output or --model: present and not empty (query's "" + "/queries" is
  // /queries: it wrote into the file system's root).
  auto path = [&](size_t& i) {
    GPHR_REQUIRE(i + 1 < v.size(), gphr::InputError, "'", v[i], "' needs a path after it (", kUsage, ")");
    GPHR_REQUIRE(!v[i + 1].empty(), gphr::InputError, "'", v[i], "' is given an empty path; allowed: a ",
                 v[i] == "--model" ? "file" : "directory", " path");
    GPHR_REQUIRE(v[i + 1].rfind("--", 0) != 0, gphr::InputError, "'", v[i], "' is followed by the option '", v[i + 1],
                 "'; allowed: a path (./", v[i + 1], " for a path of that name)");
    return v[++i];
  };
  std::vector<std::string> seen;  // each option once: a second one silently replaced the first
  for (size_t i = from; i < v.size(); ++i) {
    GPHR_REQUIRE(std::find(seen.begin(), seen.end(), v[i]) == seen.end(), gphr::InputError, "'", v[i],
                 "' is given twice; allowed: each option once");
    seen.push_back(v[i]);
    GPHR_REQUIRE(!(v[i] == "--verbose" || v[i] == "--quiet") ||
                     std::find(seen.begin(), seen.end(), v[i] == "--verbose" ? "--quiet" : "--verbose") == seen.end(),
                 gphr::InputError, "'--verbose' and '--quiet' are given together; allowed: one of them");
    if (v[i] == "--output") a.output = path(i);
    else if (model && v[i] == "--model") a.model = path(i);
    else if (model && v[i] == "--target-error") {
      GPHR_REQUIRE(i + 1 < v.size(), gphr::InputError, "'--target-error' needs a number after it (", kUsage, ")");
      const std::string text = v[++i];
      char* end = nullptr;
      a.targetError = std::strtod(text.c_str(), &end);
      GPHR_REQUIRE(!text.empty() && end && *end == '\0' && std::isfinite(a.targetError) && a.targetError > 0.0 &&
                       a.targetError < 1.0,
                   gphr::InputError, "--target-error '", text, "'; allowed: a number 0 < EPS < 1 (a relative error E_L2)");
    } else if (threads && v[i] == "--threads")
      a.threads = gphr::queryThreadsFromText(i + 1 < v.size() ? v[++i] : std::string());
    else if (v[i] == "--verbose") a.verbosity = Args::Verbose;
    else if (v[i] == "--quiet") a.verbosity = Args::Quiet;
    else
      throw gphr::InputError("unknown argument '" + v[i] + "'; allowed: --output DIR" +
                             (model ? ", --model FILE, --target-error EPS" : "") +
                             (threads ? ", --threads N" : "") + ", --verbose, --quiet");
  }
}

Args parseArgs(int argc, char** argv) {
  Args a;
  std::vector<std::string> v(argv + 1, argv + argc);
  if (v.empty()) return a;  // default scene
  if (v[0] == "--output" || v[0] == "--verbose" || v[0] == "--quiet") {  // the default scene
    options(a, v, 0, false);
    return a;
  }
  if (v[0] == "--help" || v[0] == "-h" || v[0] == "help") {
    a.command = Args::Help;
    return a;
  }
  GPHR_REQUIRE(v[0] == "run" || v[0] == "build" || v[0] == "query" || v[0] == "validate", gphr::InputError,
               "unknown command '", v[0], "'; allowed: run, build, query, validate, --help (", kUsage, ")");
  if (v[0] == "query" || v[0] == "validate") {
    GPHR_REQUIRE(v.size() >= 3, gphr::InputError, "'gphr ", v[0], "' needs MODEL.h5 and a YAML file (", kUsage, ")");
    for (size_t i : {size_t(1), size_t(2)})  // "gphr query M.h5 --output D": the YAML file is missing
      GPHR_REQUIRE(v[i].rfind("--", 0) != 0, gphr::InputError, "'gphr ", v[0], "' needs MODEL.h5 and a YAML file before its "
                   "options; found the option '", v[i], "' where the ", i == 1 ? "model file" : "YAML file",
                   " belongs (", kUsage, ")");
    a.command = v[0] == "query" ? Args::Query : Args::Validate, a.model = v[1], a.queries = v[2];
    a.output = v[0] == "query" ? "gphr-queries" : "gphr-validation";
    options(a, v, 3, false, a.command == Args::Query);
    return a;
  }
  GPHR_REQUIRE(v.size() >= 2 && v[1].rfind("--", 0) != 0, gphr::InputError, "'gphr ", v[0], "' needs a CONFIG file",
               v.size() >= 2 ? " before its options; found the option '" + v[1] + "'" : std::string(), " (", kUsage, ")");
  a.config = v[1];
  a.command = v[0] == "build" ? Args::Build : Args::Run;
  options(a, v, 2, a.command == Args::Build);
  GPHR_REQUIRE(a.command != Args::Build || !a.model.empty(), gphr::InputError, "'gphr build' needs --model FILE.h5 (",
               kUsage, ")");
  return a;
}

// --quiet: progress (stderr) and results (stdout) go to /dev/null; errors to the returned stream,
// a copy of the original stderr.
FILE* quiet() {
  FILE* errors = fdopen(dup(fileno(stderr)), "w");
  std::fflush(stdout), std::fflush(stderr);
  if (!std::freopen("/dev/null", "w", stdout) || !std::freopen("/dev/null", "w", stderr) || !errors) return stderr;
  std::cout.flush();
  return errors;
}

int runMain(const Args& args, const gphr::RCP<const gphr::Comm>& comm) {
  using namespace gphr;
  const bool root = comm->getRank() == 0;
  if (!args.config.empty()) requireOutputsApart({{args.config, "the config file"}}, {{args.output, "--output"}});
  const RunOptions opt = runOptionsFrom(args.config.empty() ? defaultConfig() : loadConfig(args.config));
  ProgressWatch::configure(opt.output.progressSeconds, root);
  RunContext ctx;
  ctx.comm = comm;
  ctx.outputDir = args.output;
  makeDirectory(ctx.outputDir, comm);
  const OutputLock lock(ctx.outputDir, "run", comm);  // before an earlier run's files are touched
  prepareOutputDir(ctx, true);
  if (root)
    std::fprintf(stderr, "[gphr] scene %s, %d rank(s), output in %s\n", opt.scene->name().c_str(),
                 comm->getSize(), ctx.outputDir.c_str());
  std::unique_ptr<RomStages> rom;
  const auto& methods = opt.pipeline.methods;
  if (!methods.empty()) rom = std::make_unique<RomStages>(runOfflineStages(ctx, opt));
  const FomResult fom = runFom(opt.evaluation, *opt.scene, opt.mu, comm, opt.output.fieldStateModels());
  if (rom && std::find(methods.begin(), methods.end(), method::kRom) != methods.end()) runRom(opt, fom, *rom);
  if (rom) runHyperReduction(opt, fom, *rom);
  {
    const ProgressPhase phase("report");
    writeReport(ctx, opt, fom, rom.get());
  }
  if (root) std::cout << runTable(ctx, opt, fom, rom.get());
  if (args.verbosity == Args::Verbose) Teuchos::TimeMonitor::summarize(comm.ptr(), std::cout);
  return 0;
}

// How long a rank that failed waits for the others to fail too before it aborts the job. Errors
// of bad input and collective solver failures reach every rank within milliseconds of each other.
constexpr double kErrorAgreementSeconds = 10.0;

// The end of a run that failed on this rank, with `code`. When every rank failed (the usual case:
// input is checked and solver failures agreed on every rank), rank 0 prints its message and all
// return `code`. When some rank did not fail within kErrorAgreementSeconds -- an error only this
// rank saw, while the others wait for it in a collective -- this rank prints its own message,
// naming itself, and aborts the job with `code`, rather than leave the others waiting forever.
// The agreement is a non-blocking barrier on a communicator of its own (`agreement`, a duplicate
// of the world's), so it cannot match a collective that other ranks are blocked in.
int failed(MPI_Comm agreement, int rank, int size, FILE* errors, const char* kind, const char* what, int code) {
  if (size > 1) {
    MPI_Request request;
    MPI_Ibarrier(agreement, &request);
    int all = 0;
    const auto start = std::chrono::steady_clock::now();
    for (MPI_Test(&request, &all, MPI_STATUS_IGNORE); !all; MPI_Test(&request, &all, MPI_STATUS_IGNORE)) {
      if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > kErrorAgreementSeconds) {
        std::fprintf(errors, "gphr: %s (rank %d of %d; the other ranks did not fail with it: aborting): %s\n", kind,
                     rank, size, what);
        std::fflush(errors);
        MPI_Abort(MPI_COMM_WORLD, code);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  if (rank == 0) std::fprintf(errors, "gphr: %s: %s\n", kind, what);
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  // Kokkos::initialize answers --help itself: print ours first (it needs neither MPI nor Kokkos).
  if (argc >= 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h" || std::string(argv[1]) == "help")) {
    std::cout << gphr::helpText();
    return 0;
  }
  // gphr's arguments are read before MPI and Kokkos start, and Kokkos is given none of them:
  // Kokkos::initialize acts on its own (--kokkos-help prints its help, --kokkos-tools-library
  // loads a library, --threads=N) before gphr could refuse them. An argument error is said once
  // MPI runs (rank 0 alone prints it, every rank exits 2).
  Args args;
  std::string argumentError;
  try {
    args = parseArgs(argc, argv);
  } catch (const gphr::InputError& e) {
    argumentError = e.what();
  }
  char* programOnly[] = {argv[0], nullptr};
  int kokkosArgc = 1;
  char** kokkosArgv = programOnly;
  Tpetra::ScopeGuard scope(&kokkosArgc, &kokkosArgv);
  auto comm = Tpetra::getDefaultComm();
  const bool root = comm->getRank() == 0;
  MPI_Comm agreement = MPI_COMM_NULL;  // for failed(): its own communicator (not freed: MPI_Finalize ends it)
  MPI_Comm_dup(MPI_COMM_WORLD, &agreement);
  const int rank = comm->getRank(), size = comm->getSize();
  FILE* errors = stderr;
  const int code = [&] {
    try {
      if (!argumentError.empty()) throw gphr::InputError(argumentError);
      if (args.command == Args::Help) {
        if (root) std::cout << gphr::helpText();
        return 0;
      }
      if (args.verbosity == Args::Quiet) errors = quiet();
      if (args.command == Args::Build) return gphr::runBuild(args.config, args.model, args.output, comm, args.targetError);
      if (args.command == Args::Query) return gphr::runQuery(args.model, args.queries, args.output, comm, args.threads);
      if (args.command == Args::Validate) return gphr::runValidate(args.model, args.queries, args.output, comm);
      return runMain(args, comm);
    } catch (const gphr::InputError& e) {
      return failed(agreement, rank, size, errors, "error", e.what(), 2);
    } catch (const gphr::SolverError& e) {
      return failed(agreement, rank, size, errors, "solver failure", e.what(), 3);
    } catch (const std::exception& e) {
      return failed(agreement, rank, size, errors, "internal error", e.what(), 1);
    }
  }();
  // A file HDF5 could not close (a full disk) would crash HDF5's termination inside MPI_Finalize
  // (Hdf5File::closeFailed): the error is said, so end here, without finalizing.
  if (gphr::Hdf5File::closeFailed()) {
    std::fflush(nullptr);
    std::_Exit(code);
  }
  return code;
}
