#include "gphr/offline/Training.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_Time.hpp>
#include <algorithm>
#include <cstdio>
#include <functional>
#include <limits>
#include <sstream>

#include "gphr/core/ColumnFingerprint.hpp"
#include "gphr/core/CacheKey.hpp"
#include "gphr/core/Error.hpp"
#include "gphr/core/Progress.hpp"
#include "gphr/core/Provenance.hpp"
#include "gphr/core/ParameterValidation.hpp"
#include "gphr/core/RankGroups.hpp"
#include "gphr/online/TimeLoop.hpp"
#include "gphr/timeint/FullModelIntegrator.hpp"
#include "gphr/timeint/ObservedTimeLoop.hpp"

namespace gphr {

std::vector<std::vector<double>> trainingGrid(const ParameterBox& box, const std::vector<int>& points) {
  const size_t p = box.names.size();
  GPHR_REQUIRE(points.size() == p, InputError, "key 'training.points' has ", points.size(), " entries; allowed: ", p,
               " (one per parameter of the box)");
  for (int c : points)
    GPHR_REQUIRE(c >= 1 && c <= 10000, InputError, "key 'training.points' has entry ", c,
                 "; allowed: integers in [1, 10000]");
  std::vector<std::vector<double>> out;
  std::vector<size_t> idx(p, 0);
  for (;;) {  // first parameter fastest
    std::vector<double> mu(p);
    for (size_t d = 0; d < p; ++d) {
      const auto [lo, hi] = box.bounds[d];
      mu[d] = points[d] == 1 ? 0.5 * (lo + hi) : lo + (hi - lo) * idx[d] / (points[d] - 1);
    }
    out.push_back(mu);
    size_t d = 0;
    while (d < p && ++idx[d] == static_cast<size_t>(points[d])) idx[d++] = 0;
    if (d == p) return out;
  }
}

TrainingOptions trainingOptionsFrom(const Teuchos::ParameterList& tr, const ParameterBox& box) {
  TrainingOptions o;
  const auto& values = tr.get<Teuchos::Array<double>>("values");
  const size_t p = box.names.size();
  if (!values.empty()) {
    GPHR_REQUIRE(values.size() % static_cast<long>(p) == 0, InputError, "key 'training.values' has ", values.size(),
                 " numbers; allowed: a multiple of ", p, " (one value per parameter of the box, in order)");
    for (size_t i = 0; i < static_cast<size_t>(values.size()); i += p)
      o.parameters.emplace_back(values.begin() + i, values.begin() + i + p);
  } else {
    const auto& pts = tr.get<Teuchos::Array<int>>("points");
    o.parameters = trainingGrid(box, std::vector<int>(pts.begin(), pts.end()));
  }
  for (const auto& mu : o.parameters) {
    try {
      box.check(mu);
    } catch (const InputError& e) {
      throw InputError(detail::concat("training set: ", e.what()));
    }
  }
  o.snapshotEvery = tr.get<int>("snapshotEvery");
  if (tr.isParameter("groupSize")) o.groupSize = tr.get<int>("groupSize");
  return o;
}

std::string trainingCacheKey(const std::string& sceneConfig, const TrainingOptions& o) {
  std::vector<double> flat;
  for (const auto& mu : o.parameters) flat.insert(flat.end(), mu.begin(), mu.end());
  return trainingStatesKey(sceneConfig, o) +
         CacheKey("training parameters", 1).add("parameters", flat).add("parameterCount", static_cast<long>(o.parameters.size())).str();
}

std::string trainingStatesKey(const std::string& sceneConfig, const TrainingOptions& o) {
  return CacheKey("training", 2)
      .add("scene", sceneConfig)
      .add("dt", o.dt)
      .add("steps", o.steps)
      .add("snapshotEvery", o.snapshotEvery)
      .add("integrator", toYaml(o.integrator))
      .str();
}

Teuchos::ParameterList trainingValidParameters(size_t parameters) {
  Teuchos::ParameterList tr("training");
  tr.set("points", Teuchos::Array<int>(static_cast<int>(parameters), 3),
         "training grid: equispaced points per parameter of the box (paper: [11] NLS, [5, 5] SWE)");
  tr.set("values", Teuchos::Array<double>(),
         "explicit training parameters, flattened (one value per box parameter each); overrides points");
  setIntParameter(tr, "snapshotEvery", 1, 1, 1000000, "keep every N-th state of each training run");
  setIntParameter(tr, "groupSize", 0, 0, 1000000,
                  "ranks per training group: the ranks split into groups that integrate their own training "
                  "parameters side by side; 0: the group count with the fewest rounds per rank of a group (a group "
                  "per parameter where the ranks allow), none splitting a system below 4096 or above 2^18 state rows per rank; the "
                  "snapshots are the same to round-off");
  return tr;
}

namespace {

std::string datasetName(size_t j) { return "/training/p" + std::to_string(j); }

// A SnapshotSet::Loader's read of parameter j's states (count kAll: all from first on), checked
// against the fingerprint the training stored (a changed value in the file would otherwise go into
// the bases unseen). Not redone in place: the reader may be one rank group, and the file is open
// read-only; the message says how to start afresh.
RCP<const MultiVector> readBlock(const Hdf5File& f, size_t j, const PhaseSpace& ps, size_t every, size_t first,
                                 size_t count) {
  auto X = f.readStates(datasetName(j), ps, every, first, count == SnapshotSet::kAll ? Hdf5File::kAllRows : count);
  const std::string problem = ArtifactsCache::fingerprintProblem(f, datasetName(j), *X, every, first);
  GPHR_REQUIRE(problem.empty(), InputError, "artifacts file '", f.path(), "': the snapshots of training parameter ",
               j + 1, " (", datasetName(j), "): ", problem,
               ": the file changed after it was written (by another program, or a machine crash before the data "
               "reached the disk); remove '",
               f.path(), "' (or use another --output directory) to train afresh");
  return X;
}

// One line per parameter on rank 0: which, reused or done, elapsed and an estimate of what is left.
class Progress {
 public:
  explicit Progress(bool show) : show_(show), clock_("train") { clock_.start(); }
  /// Parameter j of `total` done (or reused); `computed` of `toCompute` integrated so far.
  void done(size_t j, size_t total, size_t computed, size_t toCompute, const std::vector<double>& mu, bool reused) {
    if (!show_) return;
    const double el = clock_.totalElapsedTime(true);
    std::ostringstream m;
    for (double x : mu) m << (m.tellp() ? ", " : "") << x;
    progressLine("[gphr] train: parameter %zu/%zu (%s) %s, %.1f s elapsed, ~%.1f s left", j + 1, total,
                 m.str().c_str(), reused ? "reused from file" : "done", el,
                 computed ? el / computed * (toCompute - computed) : 0.0);
  }

 private:
  bool show_;
  Teuchos::Time clock_;
};

// A cache trained with another key is emptied (its snapshots and the basis built from them).
void startCache(const ArtifactsCache& cache, const std::string& key) {
  auto f = cache.open();
  if (!f->exists("/training")) f->createGroup("/training");
  const bool trained = f->hasAttribute("/training", "config");
  if (trained && f->stringAttribute("/training", "config") == key) return;
  if (trained && cache.comm()->getRank() == 0)
    std::fprintf(stderr, "[gphr] train: the training config changed; training again\n");
  for (size_t j = 0; f->exists(datasetName(j)); ++j) f->remove(datasetName(j));
  f->remove("/basis");
  f->setAttribute("/training", "config", key);
}

// The same states handed to `store` kSnapshotReadColumns at a time, in order (the last block
// shorter), so that a trajectory of any length holds one block: the sequence of block sizes is
// blockSizes(columns), the same for every parameter.
void integrateInBlocks(const SceneInstance& inst, const TrainingOptions& o,
                       const std::function<void(const MultiVector&)>& store) {
  FullModelIntegrator integ(inst.system, o.integrator);
  const size_t columns = static_cast<size_t>(o.steps / o.snapshotEvery + 1);
  MultiVector block(inst.system->map(), std::min(kSnapshotReadColumns, columns));
  size_t filled = 0, stored = 0;
  Vector y(*inst.y0, Teuchos::Copy);
  const std::function<void(long, double, const Vector&)> observe = [&](long s, double, const Vector& ys) {
    if (s % o.snapshotEvery != 0) return;
    Tpetra::deep_copy(*block.getVectorNonConst(filled), ys);
    if (++filled < block.getNumVectors() && stored + filled < columns) return;
    store(*block.subView(Teuchos::Range1D(0, filled - 1)));
    stored += filled, filled = 0;
  };
  // The one observed loop: a non-finite state ends it (never a snapshot); the training's full model
  // is a reference, so its divergence is the training's error (runTraining names the parameter).
  const SimulationStats sim = observedTimeLoop(integ, y, o.dt, o.steps, observe);
  if (!sim.ok()) throw SolverError(sim.reason);
  GPHR_REQUIRE(stored == columns, SolverError, "training: the integrator handed ", stored, " of the ", columns,
               " states to store");
}

// The shifted snapshots of one training parameter's instance, all held (the training without a cache).
RCP<MultiVector> integrate(const SceneInstance& inst, const TrainingOptions& o) {
  auto snaps = rcp(new MultiVector(inst.system->map(), o.steps / o.snapshotEvery + 1));
  size_t filled = 0;
  integrateInBlocks(inst, o, [&](const MultiVector& block) {
    const size_t b = block.getNumVectors();
    Tpetra::deep_copy(*snaps->subViewNonConst(Teuchos::Range1D(filled, filled + b - 1)), block);
    filled += b;
  });
  return snaps;
}

// The sizes of the blocks integrateInBlocks hands over for `columns` states.
std::vector<size_t> blockSizes(size_t columns) {
  std::vector<size_t> b;
  for (size_t c0 = 0; c0 < columns; c0 += kSnapshotReadColumns) b.push_back(std::min(kSnapshotReadColumns, columns - c0));
  return b;
}

}  // namespace

// The group count G that finishes the P parameters soonest with ideal scaling inside a group:
// the least ceil(P / G) rounds per floor(p / G) ranks, among the G whose groups hold a system
// (p / G >= ceil(rows / 2^18) ranks) and do not split it below 4096 rows per rank (p / G <=
// ceil(rows / 4096)); where no G does both, the groups of ceil(rows / 4096) ranks. Ties go to
// more groups: SWE 256^2's 4 parameters on 16 ranks, groups of 4 against 8 (1 or 2 rounds, whose
// sums even out the parameters' costs), training critical path 2.65, 2.72 s against 2.90, 3.11 s
// on the 2-core VM (doc/scaling.md, "Critical path"). SWE 256^2 (131,072 rows), 4 parameters: 2
// groups of 1 on 2 ranks (training 1.95x; one group of 2: 1.44x), 4 of 4 on 16; the NLS (4096
// rows): groups of 1; 10^8 rows, 5 parameters on 1024 ranks: one group (two of 512 take 3 rounds:
// 3 / 512 > 5 / 1024).
int trainingGroupSize(long fullDim, int ranks, long parameters) {
  const long p = ranks, P = std::max<long>(parameters, 1);
  const long worth = (fullDim + kTrainingRowsPerRank - 1) / kTrainingRowsPerRank;     // most ranks per system
  const long hold = (fullDim + kMaxTrainingRowsPerRank - 1) / kMaxTrainingRowsPerRank;  // fewest ranks per system
  const long most = std::max<long>(1, std::min(P, p / hold)), fewest = (p + worth - 1) / worth;
  if (fewest > most) return static_cast<int>(std::clamp<long>(p / std::min(fewest, p), 1, p));
  // Time ~ ceil(P / G) rounds / (p / G ranks): compared as fractions, a / b < c / d <=> a d < c b.
  auto rounds = [&](long G) { return (P + G - 1) / G; };
  long best = most;
  for (long G = most; G >= fewest; --G)
    if (rounds(G) * (p / best) < rounds(best) * (p / G)) best = G;
  return static_cast<int>(std::clamp<long>(p / best, 1, p));
}

namespace {

// Which parameters the cache holds complete for `key` and their own parameter values (exactly:
// the dataset's `parameters` attribute), so that a training set grown by appending parameters
// trains the new ones only; a half-written one, or one of other values, is removed (redone).
std::vector<char> completeInCache(const ArtifactsCache& cache, const TrainingOptions& o, const std::string& key) {
  const size_t count = o.parameters.size();
  std::vector<char> done(count, 0);
  const auto f = cache.open();
  for (size_t j = 0; j < count; ++j) {
    const std::string name = datasetName(j);
    // one without its fingerprint (an older gphr's) is trained again: its reads could not be checked
    done[j] = ArtifactsCache::holds(*f, name, key) && f->hasAttribute(name, "fingerprint") &&
              f->hasAttribute(name, "parameters") && f->doubleAttribute(name, "parameters") == o.parameters[j];
    if (!done[j]) f->remove(name);
  }
  for (size_t j = count; f->exists(datasetName(j)); ++j) f->remove(datasetName(j));  // beyond the set: not ours
  return done;
}

// Parameter c's fingerprint on every rank of `world`: its group's first rank adds its own
// (`print`, of parameter j), every other rank zeros (a sum with zeros is exact). One parameter at a
// time: a rank holds one trajectory's fingerprint, not a round's.
std::vector<double> parameterFingerprint(const Comm& world, const Comm& group, size_t c, size_t j,
                                         const std::vector<double>& print, size_t columns) {
  std::vector<double> mine(columns, 0.0), all(columns);
  if (c == j && group.getRank() == 0) mine = print;
  GPHR_REQUIRE(mine.size() == columns, SolverError, "training: a fingerprint of ", mine.size(), " of the ", columns,
               " states");
  Teuchos::reduceAll(world, Teuchos::REDUCE_SUM, static_cast<int>(columns), mine.data(), all.data());
  return all;
}

// One round of the training with the cache (collective over the cache's ranks): group g
// integrates parameter slots[g] on `groupComm` (none: max size_t; no slot holds a parameter the
// cache has done) while the round's datasets fill block by block: at each of integrateInBlocks'
// blocks every rank of the world opens the file, each dataset's rows are written by its group's
// ranks straight from their rows (Hdf5File::writeStateRows; the other ranks select nothing, and a
// group with nothing to integrate takes part with nothing) and the file is closed. At the end the
// round's parameters are sealed together (their marks; one flush to the disk first where the cache
// syncs). So the training holds one block of states per rank, not a trajectory; the file is
// closed between blocks, and a kill loses the unfinished round only (its datasets carry no complete
// mark). A group whose full model fails (a SolverError: Newton did not converge) stops integrating but
// still takes part in the round's remaining block writes, and all ranks then agree on the failure
// and throw it, naming the parameter: no group is left waiting in a collective write for one that
// stopped.
// (Each group writing a parallel HDF5 file of its own, copied into the cache at the end, moved
// every snapshot through the file system twice more: 0.68 s of the 7.4 s training of SWE 256^2 on
// 16 ranks. Moving each parameter to all ranks first by a Tpetra Import, then writing, took
// 0.18-0.27 s a parameter of SWE 256^2 on the 2-core VM's 2 ranks, against 0.06 s for the write;
// Teuchos timers in a local build, not kept.)
void trainRound(const Scene& scene, const RCP<const Comm>& groupComm, int group, const std::vector<size_t>& slots,
                const TrainingOptions& o, const ArtifactsCache& cache, const std::string& key, hsize_t fullDim) {
  const size_t count = o.parameters.size(), none = std::numeric_limits<size_t>::max();
  const size_t j = slots.at(static_cast<size_t>(group));
  const size_t columns = static_cast<size_t>(o.steps / o.snapshotEvery + 1);
  std::vector<size_t> round;
  for (size_t c : slots)
    if (c != none) round.push_back(c);
  if (round.empty()) return;
  {
    const auto f = cache.open();
    for (size_t c : round) {
      ArtifactsCache::clear(*f, datasetName(c));
      f->createStates(datasetName(c), columns, fullDim);
    }
  }
  hsize_t row = 0;
  auto store = [&](const MultiVector* block, const PhaseSpace* space, size_t b) {
    const auto f = cache.open();
    for (size_t c : round)
      f->writeStateRows(datasetName(c), row, b, c == j ? block : nullptr, c == j ? space : nullptr);
    row += b;
  };
  size_t stored = 0;         // blocks this rank's group stored
  std::vector<double> print;  // their fingerprint (ColumnFingerprint.hpp), block by block
  GroupFailure failure;      // what its parameter threw, if anything (its full model's SolverError, say)
  if (j != none)
    failure = failureOf(detail::concat("training parameter ", j + 1, " of ", count), "the full model failed: ", [&] {
      const SceneInstance inst = scene.instantiate(groupComm, o.parameters[j], true);
      integrateInBlocks(inst, o, [&](const MultiVector& block) {
        store(&block, &inst.system->space(), block.getNumVectors());
        ++stored;  // before anything else can throw: the blocks left below are the ones not written
        const std::vector<double> fp = columnFingerprint(block);
        print.insert(print.end(), fp.begin(), fp.end());
      });
    });
  const std::vector<size_t> sizes = blockSizes(columns);
  for (size_t b = stored; b < sizes.size(); ++b) store(nullptr, nullptr, sizes[b]);  // nothing (more) of ours
  agreeOnFailure(*cache.comm(), failure);
  const auto f = cache.open();
  std::vector<std::string> names;
  for (size_t c : round) {
    f->setAttribute(datasetName(c), "parameters", o.parameters[c]);
    ArtifactsCache::stampFingerprint(*f, datasetName(c),
                                     parameterFingerprint(*cache.comm(), *groupComm, c, j, print, columns));
    names.push_back(datasetName(c));
  }
  cache.seal(*f, names, key);  // one flush for the round, where the cache syncs to disk
}

// The parameters not in the cache in rounds of G: rank groups (TrainingOptions::groupSize) when
// size < the ranks, one group of all ranks (a round per parameter) otherwise. Parameter c belongs to
// group c mod G whatever the cache holds (so a resumed or grown training integrates each on the
// same ranks as a whole one: the same bits), and round r trains the r-th of each group's own
// parameters not yet done: parameters appended to a trained set (a greedy round's) go side by side.
// Returns the rounds.
long trainInRounds(const Scene& scene, const RCP<const Comm>& comm, const TrainingOptions& o,
                   const ArtifactsCache& cache, const std::string& key, const std::vector<char>& done, int size,
                   const PhaseSpace& ps) {
  const bool split = size < comm->getSize();
  const RankGroups groups(comm, split ? size : comm->getSize());
  const size_t G = static_cast<size_t>(groups.count()), count = o.parameters.size();
  const size_t none = std::numeric_limits<size_t>::max();
  std::vector<std::vector<size_t>> queue(G);  // per group, its parameters to train, in order
  for (size_t c = 0; c < count; ++c)
    if (!done[c]) queue[c % G].push_back(c);
  size_t rounds = 0, toCompute = 0;
  for (const auto& q : queue) rounds = std::max(rounds, q.size()), toCompute += q.size();
  Progress progress(o.progress && comm->getRank() == 0);
  size_t computed = 0;
  for (size_t c = 0; c < count; ++c)
    if (done[c]) progress.done(c, count, computed, toCompute, o.parameters[c], true);
  for (size_t r = 0; r < rounds; ++r) {
    std::vector<size_t> slots(G, none);
    for (size_t g = 0; g < G; ++g)
      if (r < queue[g].size()) slots[g] = queue[g][r];
    trainRound(scene, split ? groups.sub() : comm, split ? groups.group() : 0, slots, o, cache, key,
               static_cast<hsize_t>(ps.fullDim()));
    std::sort(slots.begin(), slots.end());  // reported in the set's order (none, the largest, last)
    for (size_t c : slots)
      if (c != none) progress.done(c, count, ++computed, toCompute, o.parameters[c], false);
  }
  if (split && o.progress && comm->getRank() == 0)
    std::fprintf(stderr, "[gphr] train: %zu groups of %d rank(s) integrated side by side\n", G, size);
  return static_cast<long>(rounds);
}

}  // namespace

TrainingResult runTraining(const Scene& scene, const RCP<const Comm>& comm, const TrainingOptions& o,
                           const ArtifactsCache* cache, const std::string& key) {
  GPHR_REQUIRE(!o.parameters.empty(), InputError, "the training set is empty; allowed: at least one parameter");
  GPHR_REQUIRE(o.groupSize >= 0, InputError, "training group size ", o.groupSize, "; allowed: 0 (automatic) or >= 1");
  Teuchos::Time clock("train");
  clock.start();
  TrainingResult res;
  res.parameters = o.parameters;
  const auto probe = scene.instantiate(comm, o.parameters[0], true);
  const PhaseSpace& ps = probe.system->space();
  const size_t count = o.parameters.size(), columns = static_cast<size_t>(o.steps / o.snapshotEvery + 1);
  if (!cache) {  // in memory, on all ranks together
    std::vector<RCP<const MultiVector>> held;
    Progress progress(o.progress && comm->getRank() == 0);
    for (size_t j = 0; j < count; ++j) {
      try {  // all ranks integrate together, so all fail together: named as in the rounds below
        held.push_back(integrate(scene.instantiate(comm, o.parameters[j], true), o));
      } catch (const SolverError& e) {
        throw SolverError(detail::concat("training parameter ", j + 1, " of ", count, ": the full model failed: ", e.what()));
      }
      progress.done(j, count, j + 1, count, o.parameters[j], false);
    }
    res.snapshots = SnapshotSet(held);
    res.seconds = clock.stop();
    return res;
  }
  startCache(*cache, key);
  const std::vector<char> done = completeInCache(*cache, o, key);
  res.reused = std::count(done.begin(), done.end(), 1);
  const int size = o.groupSize > 0 ? std::min(o.groupSize, comm->getSize())
                                   : trainingGroupSize(ps.fullDim(), comm->getSize(), static_cast<long>(count));
  res.groupSize = size;
  res.cachePath = cache->path();
  res.rounds = trainInRounds(scene, comm, o, *cache, key, done, size, ps);
  const std::string path = cache->path();
  const RCP<const HamiltonianSystem> system = probe.system;  // keeps the phase space of the blocks
  res.snapshots = SnapshotSet(std::vector<size_t>(count, columns),
                              [path, comm, system](size_t j, size_t every, size_t first, size_t n) {
                                Hdf5File f(path, comm, Hdf5File::Mode::ReadOnly);
                                return readBlock(f, j, system->space(), every, first, n);
                              });
  res.seconds = clock.stop();
  return res;
}

SnapshotSet trainingSnapshotsOn(const TrainingResult& training, const RCP<const Comm>& comm, const PhaseSpace& space) {
  GPHR_REQUIRE(!training.cachePath.empty(), InputError,
               "training snapshots on a rank group: the training holds its snapshots in memory; allowed: a training "
               "with an artifacts cache");
  std::vector<size_t> columns;
  for (size_t j = 0; j < training.snapshots.size(); ++j) columns.push_back(training.snapshots.numColumns(j));
  const std::string path = training.cachePath;
  const PhaseSpace* ps = &space;  // the caller's system keeps it alive while the set is used
  return SnapshotSet(columns, [path, comm, ps](size_t j, size_t every, size_t first, size_t n) {
    Hdf5File f(path, comm, Hdf5File::Mode::ReadOnly);
    return readBlock(f, j, *ps, every, first, n);
  });
}

SystemSet trainingSystems(const Scene& scene, const RCP<const Comm>& comm, const TrainingResult& training) {
  const Scene* s = &scene;
  const auto parameters = training.parameters;
  return SystemSet(parameters.size(), [s, comm, parameters](size_t j) -> RCP<const HamiltonianSystem> {
    return s->instantiate(comm, parameters[j], true).system;
  });
}

}  // namespace gphr
