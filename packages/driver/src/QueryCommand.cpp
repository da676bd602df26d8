// `gphr query MODEL.h5 QUERIES.yaml --output DIR`: the file's hyper-reduced models at many
// parameters. Queries are dealt round-robin to the ranks, each run on one rank alone (the online
// model is small and replicated: no communication in the time loop), and within a rank to a pool of
// --threads std::threads (QueryThreads.hpp), each query on one thread alone with its own online
// model, so a query's result depends on neither count. Each finished query is written at once to DIR/queries/<name>.h5
// (write-then-rename) with a key of everything that determines it: a killed run restarts without
// redoing them. Rank 0 then gathers them into DIR/results.h5, DIR/queries.csv and
// DIR/query_summary.json.
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_DefaultSerialComm.hpp>
#include <Teuchos_Time.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

#include "gphr/core/Provenance.hpp"
#include "gphr/core/Error.hpp"
#include "gphr/core/Progress.hpp"
#include "gphr/core/Fnv1a.hpp"
#include "gphr/driver/QueryCommand.hpp"
#include "gphr/driver/OutputDirectory.hpp"
#include "gphr/driver/Json.hpp"
#include "gphr/driver/OutputLock.hpp"
#include "gphr/driver/QueryList.hpp"
#include "gphr/driver/QueryThreads.hpp"
#include "gphr/driver/XdmfWriter.hpp"
#include "gphr/online/ReducedModel.hpp"
#include "gphr/core/Method.hpp"
#include "gphr/io/Hdf5File.hpp"

namespace gphr {

namespace {

RCP<const Comm> selfComm() { return rcp(new Teuchos::SerialComm<int>()); }

// Held by a query thread for HDF5 (Debian's library is not built thread-safe) and for an online
// model's set-up (setup: exact instantiates the full system on Tpetra and reads the basis; the
// interpolated one parses the file's integrator settings): what runs unlocked is the online
// model's own time loop and its kernels, on data of that model alone.
std::mutex serialPart;

std::string queryFile(const std::string& dir, const Query& q) { return dir + "/queries/" + q.name + ".h5"; }

// The datasets of a query's file that DIR/results.h5 gathers (those present).
constexpr const char* kResultDatasets[] = {"/hamiltonian", "/saved_times", "/z", "/probes", "/states"};

// FNV-1a over those datasets as stored (names, shapes, values): the `checksum` attribute of a
// query's file, so that a reused result is the one written (HDF5 checks only the headers).
std::string resultChecksum(const Hdf5File& f) {
  Fnv1a h;
  for (const char* name : kResultDatasets) {
    if (!f.exists(name)) continue;
    size_t rows = 0, cols = 0;
    const auto v = f.readArray(name, &rows, &cols);
    h.text(name);
    h.numbers(std::vector<double>{double(rows), double(cols)});
    h.numbers(v);
  }
  return h.hex();
}

// A finished query as the CSV and the summary see it.
struct QueryOutcome {
  bool known = false;  ///< run or read on this rank (shareOutcomes fills the others)
  RunStatus status = RunStatus::Ok;
  std::string reason;
  double setupSeconds = NAN, onlineSeconds = NAN, drift = NAN, newtonIterations = NAN;
  /// the calibrated error estimate, the raw indicator and its seconds (NaN: none, ErrorIndicator.hpp)
  double errorEstimate = NAN, errorIndicator = NAN, indicatorSeconds = NAN;
  bool extrapolated = false, reused = false;
};

// The numbers a query's file and the ranks' exchange carry, in this order.
constexpr size_t kOutcomeNumbers = 8;
std::vector<double> outcomeNumbers(const QueryOutcome& o) {
  return {o.setupSeconds, o.onlineSeconds, o.drift, o.newtonIterations, o.extrapolated ? 1.0 : 0.0,
          o.errorEstimate, o.errorIndicator, o.indicatorSeconds};
}
void setOutcomeNumbers(QueryOutcome& o, const std::vector<double>& v) {
  GPHR_REQUIRE(v.size() == kOutcomeNumbers, InputError, v.size(), " outcome numbers; allowed: ", kOutcomeNumbers);
  o.setupSeconds = v[0], o.onlineSeconds = v[1], o.drift = v[2], o.newtonIterations = v[3];
  o.extrapolated = v[4] != 0.0;
  o.errorEstimate = v[5], o.errorIndicator = v[6], o.indicatorSeconds = v[7];
}

// The outcome stored in a finished query's file if its key matches (resultKey: the query, the
// model file's checksum, the gphr version); else the query is redone, and a file of another key
// is said to be by the rank that redoes it.
bool finished(const std::string& path, const std::string& key, QueryOutcome& out) {
  std::ifstream probe(path);
  if (!probe.good()) return false;
  try {
    Hdf5File f(path, selfComm(), Hdf5File::Mode::ReadOnly);
    if (!f.hasAttribute("/", "key") || f.stringAttribute("/", "key") != key) {
      std::fprintf(stderr, "[gphr] query: %s holds a result of another model file, query or gphr version: redone\n",
                     path.c_str());
      return false;
    }
    out.status = statusFromName(f.stringAttribute("/", "status"));
    out.known = true;
    out.reason = f.stringAttribute("/", "reason");
    setOutcomeNumbers(out, f.doubleAttribute("/", "numbers"));
    // Read here what writeResults() will copy: a damaged dataset (its header's checksum, a
    // changed value) is then a query to redo, not an error or a wrong result after every query has run.
    GPHR_REQUIRE(f.hasAttribute("/", "checksum") && f.stringAttribute("/", "checksum") == resultChecksum(f),
                 InputError, "checksum mismatch");
    out.reused = true;
    return true;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "[gphr] query: %s is unreadable or damaged (%s): redone\n", path.c_str(), e.what());
    return false;  // redo it
  }
}

struct Recorder {
  std::vector<double> H, times, z, probes;
  size_t probeCount = 0;
};

// The physical states y0(mu) + A z at the saved steps (O(n k) each: asked for with states: true).
GO writeStates(Hdf5File& f, const ReducedModel& model, const Query& q, const std::vector<double>& z, size_t saved) {
  const auto inst = model.scene().instantiate(selfComm(), q.mu, true);
  const auto A = model.basis(q.k, inst.system->space());
  const auto Z = liftWorkspace(*A, static_cast<int>(saved));
  MultiVector Y(inst.system->map(), saved);
  liftStates(*A, inst.system->reference().get(), z.data(), static_cast<int>(saved), *Z, Y);
  f.writeStates("/states", Y, inst.system->space());
  return static_cast<GO>(Y.getGlobalLength());
}

// queries/<name>.xdmf beside the query's file: its lifted states in ParaView (XdmfWriter.hpp), one
// field per component named after the model; a scene without a grid gets a line saying so instead.
void writeStatesXdmf(const std::string& h5Path, const ReducedModel& model, const Query& q,
                     const std::vector<double>& times, GO fullDim) {
  SceneGrid grid;
  try {
    grid = fieldGrid(model.scene(), fullDim);
  } catch (const InputError& e) {
    std::fprintf(stderr, "[gphr] query %s: no XDMF file: %s\n", q.name.c_str(), e.what());
    return;
  }
  const std::string label = fieldName(q.method + " k=" + std::to_string(q.k) + (q.m > 0 ? " m=" + std::to_string(q.m) : ""));
  RenameOnCommit xdmf(h5Path.substr(0, h5Path.size() - 3) + ".xdmf", selfComm());
  writeTextFile(xdmf.tempPath(), xdmfText(grid, q.name + ".h5", times, {{label, "/states"}}));
  xdmf.commit();
}

// The observer that records a query's outputs: H_hr at every step, z and the probes at the saved ones.
QueryObserver recording(const Query& q, Recorder& rec) {
  const long steps = wholeSteps(q.T, q.dt);
  const size_t saved = static_cast<size_t>(steps / q.saveEvery) + 2;  // no reallocation in the time loop
  rec.H.reserve(steps + 1);
  rec.times.reserve(saved);
  rec.z.reserve(saved * 2 * static_cast<size_t>(q.k));
  rec.probes.reserve(saved * rec.probeCount);
  return [&rec, &q, steps](const QueryStep& s) {
    rec.H.push_back(s.hamiltonian);
    if (s.step % q.saveEvery != 0 && s.step != steps) return;
    rec.times.push_back(s.time);
    rec.z.insert(rec.z.end(), s.z.values(), s.z.values() + s.z.length());
    if (rec.probeCount) rec.probes.insert(rec.probes.end(), s.probes.begin(), s.probes.end());
  };
}

QueryOutcome outcomeOf(const Query& q, const SimulationStats& stats, const Recorder& rec, double setup, bool outside) {
  QueryOutcome out;
  out.known = true;
  out.status = stats.status, out.reason = stats.reason;
  out.setupSeconds = setup, out.onlineSeconds = stats.onlineSeconds;
  out.extrapolated = outside;
  out.errorEstimate = stats.errorEstimate, out.errorIndicator = stats.errorIndicator;
  out.indicatorSeconds = stats.indicatorSeconds;
  out.newtonIterations = stats.ok() ? double(stats.run.newtonIterations) / wholeSteps(q.T, q.dt) : NAN;
  out.drift = 0.0;
  for (double h : rec.H) out.drift = std::max(out.drift, std::abs(h - rec.H.front()));
  if (!stats.ok()) out.drift = NAN;
  return out;
}

void writeQuery(const std::string& path, const ReducedModel& model, const Query& q, const Recorder& rec,
                const QueryOutcome& out) {
  RenameOnCommit commit(path, selfComm());
  GO fullDim = 0;  // of the states written, if any
  {
    Hdf5File f(commit.tempPath(), selfComm(), Hdf5File::Mode::Create);
    f.writeArray("/hamiltonian", rec.H.empty() ? std::vector<double>{NAN} : rec.H, std::max<size_t>(1, rec.H.size()), 1);
    const size_t saved = rec.times.size(), r = 2 * static_cast<size_t>(q.k);
    if (saved > 0) {
      f.writeArray("/saved_times", rec.times, saved, 1);
      f.writeArray("/z", rec.z, saved, r);
      if (rec.probeCount) f.writeArray("/probes", rec.probes, saved, rec.probeCount);
      if (q.states) fullDim = writeStates(f, model, q, rec.z, saved);
    }
    f.setAttribute("/", "parameter", q.mu);
    f.setAttribute("/", "status", std::string(statusName(out.status)));
    f.setAttribute("/", "reason", out.reason);
    f.setAttribute("/", "numbers", outcomeNumbers(out));
    f.setAttribute("/", "error_estimate", std::vector<double>{out.errorEstimate});
    f.setAttribute("/", "checksum", resultChecksum(f));
    f.flush();
    f.setAttribute("/", "key", resultKey(q, model.data()));  // last: marks the file complete
  }
  // before the query's file is final: a run killed in between redoes the query, and so the XDMF file
  if (fullDim > 0) writeStatesXdmf(path, model, q, rec.times, fullDim);
  commit.commit();
}

// A query of a sample-mesh model, on this rank alone.
QueryOutcome runOne(const ReducedModel& model, const Query& q, const std::string& path) {
  std::unique_lock<std::mutex> lock(serialPart);
  OnlineModel online = model.instantiate(q.method, q.k, q.m, q.mu, q.extrapolate, q.setup);
  lock.unlock();
  Recorder rec;
  rec.probeCount = q.probes ? online.probeGids().size() : 0;
  const auto stats = online.simulate(q.T, q.dt, recording(q, rec));
  const QueryOutcome out = outcomeOf(q, stats, rec, online.setupSeconds(), online.extrapolated());
  lock.lock();
  writeQuery(path, model, q, rec, out);
  return out;
}

// A gp-adeim query, on every rank together (the full system is distributed); rank 0 writes it and
// alone returns its outcome (shareOutcomes sums over the ranks).
QueryOutcome runAdaptive(const ReducedModel& model, const Query& q, const std::string& path,
                         const RCP<const Comm>& comm) {
  Recorder rec;
  rec.probeCount = q.probes ? model.data().basis(q.k).probeGids.size() : 0;
  double setup = NAN;
  SimulationStats stats;
  try {
    stats = model.simulateAdaptive(q.k, q.m, q.mu, q.T, q.dt, comm, recording(q, rec), &setup, q.extrapolate);
  } catch (const SolverError& e) {  // the full system's solver: collective, every rank throws it
    throw SolverError(detail::concat("query '", q.name, "' (", q.method, " k=", q.k, " m=", q.m, "): ", e.what()));
  }
  if (comm->getRank() != 0) return QueryOutcome();
  const QueryOutcome out = outcomeOf(q, stats, rec, setup, model.data().outsideBox(q.mu));
  writeQuery(path, model, q, rec, out);
  return out;
}

// Each query's outcome on every rank (rank 0 writes the table): numbers summed over the ranks,
// each query's from the rank that ran it; the status words travel as codes.
void shareOutcomes(const RCP<const Comm>& comm, std::vector<QueryOutcome>& outs) {
  const size_t n = outs.size(), w = kOutcomeNumbers + 2;  // the status code, the numbers, reused
  std::vector<double> mine(n * w, 0.0), all(n * w, 0.0);
  for (size_t i = 0; i < n; ++i) {
    if (!outs[i].known) continue;
    mine[i * w] = 1.0 + static_cast<double>(outs[i].status);  // RunStatus as a number > 0
    const auto v = outcomeNumbers(outs[i]);
    std::copy(v.begin(), v.end(), mine.begin() + i * w + 1);
    mine[i * w + w - 1] = outs[i].reused ? 1.0 : 0.0;
  }
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, static_cast<int>(mine.size()), mine.data(), all.data());
  for (size_t i = 0; i < n; ++i) {
    const double* v = all.data() + i * w;
    if (!outs[i].known) outs[i].status = static_cast<RunStatus>(static_cast<int>(v[0]) - 1), outs[i].known = true;
    setOutcomeNumbers(outs[i], std::vector<double>(v + 1, v + w - 1));
    outs[i].reused = v[w - 1] != 0.0;
  }
}

std::string number(double x) { return std::isfinite(x) ? detail::concat(x) : std::string("nan"); }

// Whether a query's estimate exceeds the file's target error (none set: never).
bool overTarget(const ReducedModelData& d, const QueryOutcome& o) {
  return d.targetError > 0.0 && std::isfinite(o.errorEstimate) && o.errorEstimate > d.targetError;
}

void writeTable(const std::string& dir, const ReducedModelData& d, const std::vector<Query>& qs,
                const std::vector<QueryOutcome>& outs) {
  std::ostringstream csv;
  {
    csv << "name";
    for (const auto& p : d.parameterNames) csv << "," << p;
    csv << ",method,k,m,T,dt,setup,status,extrapolated,error_estimate,over_target,setup_s,online_s,indicator_s,"
           "H_hr_drift_max,newton_iters_avg,reused\n";
    for (size_t i = 0; i < qs.size(); ++i) {
      const auto& q = qs[i];
      const auto& o = outs[i];
      csv << q.name;
      for (double x : q.mu) csv << "," << number(x);
      csv << "," << q.method << "," << q.k << "," << q.m << "," << number(q.T) << "," << number(q.dt) << ","
          << (methodInfo(q.method).needsFullResidual ? "full system"
              : q.setup == SetupRoute::Exact                        ? "exact"
                                                                    : "interpolated")
          << "," << statusName(o.status) << ","
          << (o.extrapolated ? "yes" : "no") << "," << number(o.errorEstimate) << ","
          << (d.targetError > 0.0 ? (overTarget(d, o) ? "yes" : "no") : "") << "," << number(o.setupSeconds) << ","
          << number(o.onlineSeconds) << "," << number(o.indicatorSeconds) << "," << number(o.drift) << "," << number(o.newtonIterations) << "," << (o.reused ? "yes" : "no") << "\n";
    }
  }
  writeTextFile(dir + "/queries.csv", csv.str());
}

// DIR/results.h5: every query's datasets under /queries/<name>, with its parameter and status.
void writeResults(const std::string& dir, const std::vector<Query>& qs) {
  RenameOnCommit commit(dir + "/results.h5", selfComm());
  {
    Hdf5File out(commit.tempPath(), selfComm(), Hdf5File::Mode::Create);
    out.createGroup("/queries");
    for (const auto& q : qs) {
      Hdf5File in(queryFile(dir, q), selfComm(), Hdf5File::Mode::ReadOnly);
      const std::string g = "/queries/" + q.name;
      out.createGroup(g);
      for (const char* name : kResultDatasets) {
        if (!in.exists(name)) continue;
        size_t rows = 0, cols = 0;
        const auto v = in.readArray(name, &rows, &cols);
        out.writeArray(g + name, v, rows, std::max<size_t>(cols, 1));
      }
      out.setAttribute(g, "parameter", q.mu);
      out.setAttribute(g, "status", in.stringAttribute("/", "status"));
      out.setAttribute(g, "error_estimate", in.doubleAttribute("/", "error_estimate"));
      out.setAttribute(g, "method", q.method);
      out.setAttribute(g, "k_m", std::vector<double>{double(q.k), double(q.m)});
    }
    out.flush();
  }
  commit.commit();
}

}  // namespace

int runQuery(const std::string& modelPath, const std::string& queriesPath, const std::string& outputDir,
             const RCP<const Comm>& comm, int threads) {
  if (threads == 0) threads = defaultQueryThreads();
  const int rank = comm->getRank(), size = comm->getSize();
  requireOutputsApart({{modelPath, "the model file"}, {queriesPath, "the queries file"}}, {{outputDir, "--output"}});
  const auto loaded = loadOnEveryRank(modelPath, comm);
  const ReducedModel& model = *loaded;
  const auto queries = readQueriesOnEveryRank(queriesPath, model, QueryFileKind::Queries, comm);
  checkLiftingBases(model, queries, QueryFileKind::Queries, comm);
  makeDirectory(outputDir, comm);
  const OutputLock lock(outputDir, "query", comm);  // before anything is made inside: a refused run leaves nothing
  makeDirectory(outputDir + "/queries", comm);
  Teuchos::Time wall("queries");
  wall.start();
  ProgressWatch::configure(2.0, rank == 0);  // gphr run's default output.progressSeconds
  const ProgressPhase phase("query: rank 0's queries");
  std::vector<QueryOutcome> outs(queries.size());
  std::vector<size_t> local, adaptive;  // this rank's share of the sample-mesh queries; the gp-adeim ones
  for (size_t i = 0, n = 0; i < queries.size(); ++i) {
    if (methodInfo(queries[i].method).needsFullResidual) adaptive.push_back(i);
    else if (n++ % size == static_cast<size_t>(rank)) local.push_back(i);
  }
  const long mine = static_cast<long>(local.size() + adaptive.size());
  long done = 0;
  double lastPrint = -1e9;
  std::mutex progress;
  for (size_t i : adaptive) {  // all ranks together, one after another
    const std::string path = queryFile(outputDir, queries[i]);
    int reuse = rank == 0 && finished(path, resultKey(queries[i], model.data()), outs[i]);
    Teuchos::broadcast(*comm, 0, Teuchos::outArg(reuse));
    if (!reuse) outs[i] = runAdaptive(model, queries[i], path, comm);
    ++done;
  }
  forEachOnThreads(local.size(), threads, [&](size_t j) {  // each outs[i] written by one thread
    const size_t i = local[j];
    const std::string path = queryFile(outputDir, queries[i]);
    std::unique_lock<std::mutex> lock(serialPart);
    const bool reuse = finished(path, resultKey(queries[i], model.data()), outs[i]);
    lock.unlock();
    if (!reuse) outs[i] = runOne(model, queries[i], path);
    const std::lock_guard<std::mutex> count(progress);
    ++done;
    const double t = wall.totalElapsedTime(true);
    if (rank == 0 && (t - lastPrint > 2.0 || done == mine)) {
      progressLine("[gphr] query: rank 0 %ld/%ld, all ranks ~%zu queries, elapsed %.1f s, ETA %.1f s", done,
                   mine, queries.size(), t, t / done * (mine - done));
      lastPrint = t;
    }
  });
  double seconds = wall.stop(), slowest = 0.0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, seconds, Teuchos::outArg(slowest));
  shareOutcomes(comm, outs);
  // rank 0 writes the tables; its failure (a full disk, say) ends every rank
  onRootAgreed(comm, "gphr query: the results", [&] {
    long ran = 0, ok = 0, over = 0, estimated = 0;
    double worst = NAN;
    for (const auto& o : outs) {
      ran += !o.reused, ok += o.status == RunStatus::Ok, over += overTarget(model.data(), o);
      if (std::isfinite(o.errorEstimate)) ++estimated, worst = std::isfinite(worst) ? std::max(worst, o.errorEstimate) : o.errorEstimate;
    }
    writeResults(outputDir, queries);
    writeTable(outputDir, model.data(), queries, outs);
    JsonObject s;
    s.set("model_file", modelPath).set("queries", static_cast<long>(queries.size())).set("queries_run", ran)
        .set("queries_reused", static_cast<long>(queries.size()) - ran).set("queries_ok", ok).set("ranks", size)
        .set("threads_per_rank", threads)
        .set("queries_with_error_estimate", estimated).set("error_estimate_max", worst)
        .set("target_error", model.data().targetError > 0.0 ? model.data().targetError : NAN)
        .set("queries_over_target", over)
        .set("wall_s", slowest).set("queries_per_s", ran > 0 ? ran / slowest : NAN).set("gphr_version", gphrVersion());
    writeTextFile(outputDir + "/query_summary.json", s.str(2) + "\n");
    std::printf("gphr query: %zu queries (%ld run, %ld reused, %ld ok) on %d rank(s) x %d thread(s) in %.2f s: "
                "%.1f queries/s; results in %s/results.h5, table %s/queries.csv\n", queries.size(), ran,
                static_cast<long>(queries.size()) - ran, ok, size, threads, slowest, ran > 0 ? ran / slowest : 0.0,
                outputDir.c_str(), outputDir.c_str());
    std::printf("  error estimate: %ld of %zu queries, largest %.3g", estimated, queries.size(), worst);
    if (model.data().targetError > 0.0)
      std::printf("; %ld over the model's target error %g (over_target in queries.csv)", over, model.data().targetError);
    std::printf("\n");
  });
  return 0;
}

}  // namespace gphr
