#include "gphr/offline/Training.hpp"

#include <Teuchos_Time.hpp>
#include <algorithm>
#include <cstdio>
#include <sstream>

#include "gphr/core/Error.hpp"
#include "gphr/core/RankGroups.hpp"
#include "gphr/online/TimeLoop.hpp"
#include "gphr/timeint/FullModelIntegrator.hpp"

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

TrainingOptions trainingOptionsFrom(const Teuchos::ParameterList& cfg, const ParameterBox& box) {
  TrainingOptions o;
  const auto& tr = cfg.sublist("training");
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
  const auto& time = cfg.sublist("time");
  o.dt = time.get<double>("dt");
  o.steps = wholeSteps(time.get<double>("T"), o.dt);
  o.snapshotEvery = tr.get<int>("snapshotEvery");
  o.integrator = cfg.sublist("integrator");
  if (tr.isParameter("groupSize")) o.groupSize = tr.get<int>("groupSize");
  return o;
}

namespace {

std::string datasetName(size_t j) { return "/training/p" + std::to_string(j); }

// One line per parameter on rank 0: which, reused or done, elapsed and an estimate of what is left.
class Progress {
 public:
  explicit Progress(bool show) : show_(show), clock_("train") { clock_.start(); }
  void done(size_t j, size_t total, size_t computed, const std::vector<double>& mu, bool reused) {
    if (!show_) return;
    const double el = clock_.totalElapsedTime(true);
    std::ostringstream m;
    for (double x : mu) m << (m.tellp() ? ", " : "") << x;
    std::fprintf(stderr, "[gphr] train: parameter %zu/%zu (%s) %s, %.1f s elapsed, ~%.1f s left\n", j + 1, total,
                 m.str().c_str(), reused ? "reused from file" : "done", el,
                 computed ? el / computed * (total - j - 1) : 0.0);
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

// The shifted snapshots of one training parameter's instance.
RCP<MultiVector> integrate(const SceneInstance& inst, const TrainingOptions& o) {
  FullModelIntegrator integ(inst.system, o.integrator);
  auto snaps = rcp(new MultiVector(inst.system->map(), o.steps / o.snapshotEvery + 1));
  Vector y(*inst.y0, Teuchos::Copy);
  integ.run(y, o.dt, o.steps, [&](long s, double, const Vector& ys, const StepReport&) {
    if (s % o.snapshotEvery == 0) Tpetra::deep_copy(*snaps->getVectorNonConst(s / o.snapshotEvery), ys);
  });
  return snaps;
}

}  // namespace

// The group count G that finishes the P parameters soonest with ideal scaling inside a group:
// the least ceil(P / G) rounds per floor(p / G) ranks (ties: more groups, less communication), among the G whose groups hold a system (p / G >= ceil(rows / 2^18) ranks) and do
// not split it below 4096 rows per rank (p / G <= ceil(rows / 4096)); where no G does both, the
// groups of ceil(rows / 4096) ranks. SWE 256^2 (131,072 rows), 4 parameters: 2 groups of 1 on 2
// ranks (training 1.95x; one group of 2: 1.44x), 4 of 4 on 16; the NLS (4096 rows): groups of 1;
// 10^8 rows, 5 parameters on 1024 ranks: one group (two of 512 take 3 rounds: 3 / 512 > 5 / 1024).
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

// Which parameters the cache holds complete for `key`; a half-written one is removed (redone).
std::vector<char> completeInCache(const ArtifactsCache& cache, size_t count, const std::string& key) {
  std::vector<char> done(count, 0);
  const auto f = cache.open();
  for (size_t j = 0; j < count; ++j) {
    done[j] = ArtifactsCache::holds(*f, datasetName(j), key);
    if (!done[j]) f->remove(datasetName(j));
  }
  return done;
}

// Parameter j's snapshots into the cache, sealed (collective over the cache's ranks). `write`
// writes the dataset. Written when the parameter has finished, the file closed between
// parameters: a kill during the next one leaves this one intact.
template <class Write>
void storeInCache(const ArtifactsCache& cache, size_t j, const std::vector<double>& mu, const std::string& key,
                  Write&& write) {
  const auto f = cache.open();
  write(*f, datasetName(j));
  f->setAttribute(datasetName(j), "parameters", mu);
  ArtifactsCache::seal(*f, datasetName(j), key);
}

// Rank groups (TrainingOptions::groupSize), in rounds: in round t group g integrates parameter
// t G + g on its own ranks; then each of the round's parameters goes into the cache in parameter
// order, sealed, written by its group's ranks straight from their rows (Hdf5File::writeStatesFrom;
// the other ranks select nothing). A round's parameters are kept when a later round is killed.
// (Each group writing a parallel HDF5 file of its own, copied into the cache at the end, moved
// every snapshot through the file system twice more: 0.68 s of the 7.4 s training of SWE 256^2 on
// 16 ranks. Moving each parameter to all ranks first by a Tpetra Import, then writing, took
// 0.18-0.27 s a parameter of SWE 256^2 on the 2-core VM's 2 ranks, against 0.06 s for the write;
// Teuchos timers in a local build, not kept.)
void trainInGroups(const Scene& scene, const RCP<const Comm>& comm, const TrainingOptions& o, const ArtifactsCache& cache,
                   const std::string& key, const std::vector<char>& done, int size, const PhaseSpace& ps) {
  const RankGroups split(comm, size);
  const size_t groups = static_cast<size_t>(split.count()), count = o.parameters.size();
  const size_t columns = static_cast<size_t>(o.steps / o.snapshotEvery + 1);
  Progress progress(o.progress && comm->getRank() == 0);
  size_t computed = 0;
  for (size_t first = 0; first < count; first += groups) {
    const size_t j = first + static_cast<size_t>(split.group()), last = std::min(first + groups, count);
    RCP<MultiVector> mine;
    SceneInstance inst;  // the group's system: its phase space says which rows this rank writes
    if (j < count && !done[j]) {
      inst = scene.instantiate(split.sub(), o.parameters[j], true);
      mine = integrate(inst, o);
    }
    for (size_t c = first; c < last; ++c) {
      const bool ours = c == j && !mine.is_null();
      if (!done[c])
        storeInCache(cache, c, o.parameters[c], key, [&](Hdf5File& f, const std::string& name) {
          f.writeStatesFrom(name, columns, static_cast<hsize_t>(ps.fullDim()), ours ? mine.get() : nullptr,
                            ours ? &inst.system->space() : nullptr);
        });
      progress.done(c, count, done[c] ? computed : ++computed, o.parameters[c], done[c]);
    }
  }
  if (o.progress && comm->getRank() == 0)
    std::fprintf(stderr, "[gphr] train: %zu groups of %d rank(s) integrated side by side\n", groups, size);
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
      held.push_back(integrate(scene.instantiate(comm, o.parameters[j], true), o));
      progress.done(j, count, j + 1, o.parameters[j], false);
    }
    res.snapshots = SnapshotSet(held);
    res.seconds = clock.stop();
    return res;
  }
  startCache(*cache, key);
  const std::vector<char> done = completeInCache(*cache, count, key);
  res.reused = std::count(done.begin(), done.end(), 1);
  const int size = o.groupSize > 0 ? std::min(o.groupSize, comm->getSize())
                                   : trainingGroupSize(ps.fullDim(), comm->getSize(), static_cast<long>(count));
  res.groupSize = size;
  res.cachePath = cache->path();
  if (size < comm->getSize()) {
    trainInGroups(scene, comm, o, *cache, key, done, size, ps);
  } else {
    Progress progress(o.progress && comm->getRank() == 0);
    size_t computed = 0;
    for (size_t j = 0; j < count; ++j) {
      if (!done[j]) {  // integrated before the file opens: a kill while integrating leaves it closed
        const RCP<const MultiVector> snaps = integrate(scene.instantiate(comm, o.parameters[j], true), o);
        storeInCache(*cache, j, o.parameters[j], key,
                     [&](Hdf5File& f, const std::string& name) { f.writeStates(name, *snaps, ps); });
      }
      progress.done(j, count, done[j] ? computed : ++computed, o.parameters[j], done[j]);
    }
  }
  const std::string path = cache->path();
  const RCP<const HamiltonianSystem> system = probe.system;  // keeps the phase space of the blocks
  res.snapshots = SnapshotSet(std::vector<size_t>(count, columns),
                              [path, comm, system](size_t j, size_t every) -> RCP<const MultiVector> {
                                Hdf5File f(path, comm, Hdf5File::Mode::ReadOnly);
                                return f.readStates(datasetName(j), system->space(), every);
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
  return SnapshotSet(columns, [path, comm, ps](size_t j, size_t every) -> RCP<const MultiVector> {
    Hdf5File f(path, comm, Hdf5File::Mode::ReadOnly);
    return f.readStates(datasetName(j), *ps, every);
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
