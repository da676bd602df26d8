#include "gphr/offline/DeimBasisStage.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_Time.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gphr/core/ColumnFingerprint.hpp"
#include "gphr/core/Error.hpp"
#include "gphr/core/Progress.hpp"
#include "gphr/core/RankGroups.hpp"
#include "gphr/offline/PodCheckpoint.hpp"

namespace gphr {

namespace {

bool readDeimBasis(const Hdf5File& f, const std::string& name, const std::string& key,
                   const HamiltonianSystem& reference, CachedDeimBasis& out) {
  if (!ArtifactsCache::holds(f, name, key)) return false;
  out.basis.U = f.readColumns(name, reference.nonlinearTerm().rowMap());
  // one that no longer matches its fingerprint (a changed value) is computed again
  const std::string problem = ArtifactsCache::fingerprintProblem(f, name, *out.basis.U);
  if (!problem.empty()) {
    if (out.basis.U->getMap()->getComm()->getRank() == 0)
      std::fprintf(stderr, "[gphr] deim basis: %s in '%s' %s: computed afresh\n", name.c_str(), f.path().c_str(),
                   problem.c_str());
    out.basis.U = Teuchos::null;
    return false;
  }
  out.basis.singularValues = f.doubleAttribute(name, "singularValues");
  out.basis.snapshots = static_cast<long>(f.doubleAttribute(name, "snapshots")[0]);
  out.computeSeconds = f.hasAttribute(name, "seconds") ? f.doubleAttribute(name, "seconds")[0] : NAN;
  out.cached = true;
  return true;
}

void writeDeimBasis(const ArtifactsCache& cache, Hdf5File& f, const std::string& name, const std::string& key,
                    const CachedDeimBasis& d) {
  ArtifactsCache::clear(f, name);
  f.writeColumns(name, *d.basis.U);
  ArtifactsCache::stampFingerprint(f, name, columnFingerprint(*d.basis.U));
  f.setAttribute(name, "singularValues", d.basis.singularValues);
  f.setAttribute(name, "snapshots", std::vector<double>{double(d.basis.snapshots)});
  f.setAttribute(name, "seconds", std::vector<double>{d.computeSeconds});
  f.setAttribute(name, "layout", std::string("rows are the DEIM basis vectors U (d entries each, row-of-G order)"));
  cache.seal(f, name, key);
}

// Per chunk, what the root needs besides its modes: rank, energy, snapshots, steps by route.
constexpr int kChunkFields = 3 + PodSteps::kFields;
void putStatistics(const DeimChunkModes& c, double* out) {
  out[0] = c.rank, out[1] = c.energy, out[2] = double(c.snapshots);
  c.podSteps.put(out + 3);
}
DeimChunkModes getStatistics(const double* f) {
  DeimChunkModes c;
  c.rank = int(f[0]), c.energy = f[1], c.snapshots = long(f[2]);
  c.podSteps = PodSteps::get(f + 3);
  return c;
}

// The root's checkpoints (PodCheckpoint.hpp): after a round but the last, at most every
// checkpointSeconds() of the cache, the root POD's state,
// the chunks done, the chunks' summed statistics and the seconds so far. Restored, the root goes
// on bit for bit; the key adds the chunk size, so that a checkpoint of other chunks is not taken.
bool saveRoot(PodCheckpoint& cp, const DeimRootPod& root, int chunksDone, double seconds) {
  PodProgress at{chunksDone, std::vector<double>(kChunkFields + 1)};
  putStatistics(root.statistics(), at.extra.data());
  at.extra[kChunkFields] = seconds;
  return cp.write(root.state(), at);
}

// The chunks done by the furthest complete checkpoint (0: none), the root restored to it; `before`:
// the seconds it had taken.
int restoreRoot(PodCheckpoint& cp, DeimRootPod& root, const RCP<const Map>& rowMap, int count, double& before) {
  StreamingPod::State st;
  const PodProgress at = cp.read(rowMap, kChunkFields + 1, count, st);
  if (at.progress == 0) return 0;
  root.restore(st, getStatistics(at.extra.data()));
  before = at.extra[kChunkFields];
  return at.progress;
}

// The hierarchical POD (DeimChunks) over the training's rank groups, in rounds: in round t group
// g PODs chunk t G + g on its own ranks (from its own systems, the snapshots streamed on its
// communicator and its own copy of A); then, in chunk order, each chunk's modes move to all ranks
// (RankGroups::toWorld from the group that computed them: its columns alone) and go into the root
// POD. A rank holds its group's chunk and one chunk on the world's rows at a time: the memory
// grows with neither the snapshots nor the number of groups.
// Only the chunk PODs' replicated SVDs were the stage's time that no rank count divided (the NLS
// at the paper's size: ~2/3 of each step); G groups divide them by G.
DeimBasis deimBasisInGroups(const Scene& scene, const TrainingResult& training, const MultiVector& A,
                            const HamiltonianSystem& reference, const DeimBasisOptions& opt, const RankGroups& groups,
                            const ArtifactsCache* cache, const std::string& name, const std::string& key,
                            double& before) {
  const auto systems = trainingSystems(scene, groups.sub(), training);
  const SnapshotSet states = trainingSnapshotsOn(training, groups.sub(), systems[0]->space());
  const RCP<MultiVector> Ag = groups.toGroup(A, systems[0]->map());
  const RCP<const Map> rowMap = reference.nonlinearTerm().rowMap(), groupRows = systems[0]->nonlinearTerm().rowMap();
  const int maxRank = deimMaxRank(opt, static_cast<GO>(rowMap->getGlobalNumElements()));
  const DeimChunks chunks = deimChunks(training.snapshots, opt, static_cast<int>(A.getNumVectors()), maxRank);
  const int count = chunks.count(), G = groups.count();
  DeimRootPod root(rowMap, opt, maxRank);
  // the key names the statistics' layout too: a checkpoint with another order of the step counts is not taken
  PodCheckpoint checkpoint(cache, name,
                           detail::concat(key, ", chunks of ", chunks.perChunk,
                                          " snapshots, steps by route tsqr/replicated/stacked/tree"));
  const int resumed = restoreRoot(checkpoint, root, rowMap, count, before);
  if (resumed > 0 && groups.world()->getRank() == 0)
    std::fprintf(stderr, "[gphr] deim basis: chunks 1-%d of %d reused from file\n", resumed, count);
  std::vector<RCP<const Export>> fromGroup(G);  // group g's rows to the world's, made once
  for (int g = 0; g < G; ++g) fromGroup[g] = groups.fromGroup(g, *groupRows, rowMap);
  ReducedStateCache blocks;  // a group's chunks q, q + G: a block longer than G chunks is cut by both
  Teuchos::Time clock("chunks");
  clock.start();
  double lastLine = 0.0;
  for (int first = resumed; first < count; first += G) {
    const int q = first + groups.group(), inRound = std::min(G, count - first);
    DeimChunkModes mine;
    std::vector<double> stats(static_cast<size_t>(inRound) * kChunkFields, 0.0), all(stats.size());
    GroupFailure failure;  // agreed on before the groups meet: none waits for one that failed
    if (q < count)
      failure = failureOf("", "", [&] {  // as computeDeimBasis would throw it (every chunk alike, mostly)
        mine = deimChunkModes(systems, states, *Ag, opt, maxRank, chunks.range(q), &blocks);
      });
    agreeOnFailure(*groups.world(), failure);
    if (q < count && groups.leader()) putStatistics(mine, stats.data() + static_cast<size_t>(q - first) * kChunkFields);
    Teuchos::reduceAll(*groups.world(), Teuchos::REDUCE_SUM, static_cast<int>(stats.size()), stats.data(), all.data());
    for (int c = 0; c < inRound; ++c) {  // chunk first + c, group c's (rank 0: one zero column, statistics only)
      const DeimChunkModes chunk = getStatistics(all.data() + static_cast<size_t>(c) * kChunkFields);
      const MultiVector* own = groups.group() == c ? mine.modes.get() : nullptr;
      root.add(*groups.toWorld(own, *fromGroup[c], static_cast<size_t>(std::max(chunk.rank, 1))), chunk);
    }
    const bool kept = checkpoint.enabled() && first + inRound < count &&  // before the line: "checkpointed" is kept
                      saveRoot(checkpoint, root, first + inRound, before + clock.totalElapsedTime(true));
    const char* tail = kept ? ", checkpointed" : "";
    // A line at most every progressSeconds (ProgressWatch; every chunk where none is set), the last always.
    const double now = clock.totalElapsedTime(true), every = ProgressWatch::seconds();
    if (groups.world()->getRank() != 0 || (first + inRound < count && every > 0.0 && now - lastLine < every)) continue;
    lastLine = now;
    if (inRound == 1)
      progressLine("[gphr] deim basis: chunk %d of %d POD'd, %.1f s%s", first + 1, count, now, tail);
    else
      progressLine("[gphr] deim basis: chunks %d-%d of %d POD'd by %d groups side by side, %.1f s%s", first + 1,
                   first + inRound, count, G, now, tail);
  }
  return root.basis();
}

// Rank groups for the DEIM basis (0: none, computeDeimBasis on all ranks), when the training
// streams from the artifacts file and the exact route has more than one chunk: options.groupSize
// ranks each, or (0) as many groups as there are chunks, each of at least ceil(2n /
// kDeimRowsPerRank) ranks; one group of all ranks where that makes one (the same rounds, a
// progress line per chunk). Unlike a time step, a
// chunk's POD is not bound by its communication (its steps are one QR per rank and one small
// reduction), so groups are limited by memory: each holds the whole basis A (2n x 2k) and a
// snapshot block, 2^18 state rows per rank at most (2k = 160: 335 MB of A per rank).
int deimGroupSize(const RCP<const Comm>& comm, const TrainingResult& training, const MultiVector& A,
                  const HamiltonianSystem& reference, const DeimBasisOptions& opt) {
  GPHR_REQUIRE(opt.groupSize >= 0, InputError, "groupSize = ", opt.groupSize, "; allowed: 0 (automatic) or >= 1");
  const int p = comm->getSize();
  if (training.cachePath.empty() || opt.svd != "exact") return 0;
  const int maxRank = deimMaxRank(opt, static_cast<GO>(reference.nonlinearTerm().rowMap()->getGlobalNumElements()));
  const long chunks = deimChunks(training.snapshots, opt, static_cast<int>(A.getNumVectors()), maxRank).count();
  if (chunks <= 1) return 0;
  if (opt.groupSize > 0) return std::min(opt.groupSize, p);
  const long rows = static_cast<long>(A.getGlobalLength());
  const long smallest = std::max<long>(1, (rows + kDeimRowsPerRank - 1) / kDeimRowsPerRank);
  const long groups = std::min<long>(chunks, p / smallest);
  return groups > 1 ? static_cast<int>(p / groups) : p;
}

}  // namespace

CachedDeimBasis runDeimBasisStage(const Scene& scene, const RCP<const Comm>& comm, const TrainingResult& training,
                                  const MultiVector& A, const HamiltonianSystem& reference,
                                  const DeimBasisOptions& options, const ArtifactsCache* cache,
                                  const std::string& key, const std::string& section) {
  const int k = static_cast<int>(A.getNumVectors()) / 2;
  const std::string name = "/deim/k" + std::to_string(k), fullKey = key + ", k = " + std::to_string(k);
  Teuchos::Time clock("deim basis");
  clock.start();
  CachedDeimBasis out;
  if (cache) readDeimBasis(*cache->open(), name, fullKey, reference, out);  // closed again: the snapshots stream from it
  if (out.cached) PodCheckpoint(cache, name, fullKey).clear();  // a leftover of another run's basis, if any
  if (!out.cached) {
    double before = 0.0;  // seconds of the rounds a resumed run restored
    try {
      const int groupSize = deimGroupSize(comm, training, A, reference, options);
      out.basis = groupSize > 0
                      ? deimBasisInGroups(scene, training, A, reference, options, RankGroups(comm, groupSize), cache,
                                          name, fullKey, before)
                      : computeDeimBasis(trainingSystems(scene, comm, training), training.snapshots, A, options);
    } catch (const InputError& e) {  // e.g. podRoute 'tsqr' on too few rows per rank: name the section
      throw InputError(detail::concat(section, ": ", e.what()));
    }
    out.computeSeconds = clock.totalElapsedTime(true) + before;
    if (cache) {
      writeDeimBasis(*cache, *cache->open(), name, fullKey, out);
      PodCheckpoint(cache, name, fullKey).clear();  // their work is in the basis now
    }
  }
  out.seconds = clock.stop();
  if (comm->getRank() == 0)
    std::fprintf(stderr, "[gphr] deim basis k = %d: %zu vectors (the snapshots' numerical rank, at most maxRank) from "
                 "%ld snapshots of 2k = %d columns each%s, %.1f s\n", k, out.basis.singularValues.size(),
                 out.basis.snapshots, 2 * k, out.cached ? " (cached)" : "", out.seconds);
  return out;
}

}  // namespace gphr
