#include "gphr/offline/BasisStage.hpp"

#include <Teuchos_Time.hpp>
#include <cstdio>
#include <ctime>

#include "gphr/core/ColumnFingerprint.hpp"
#include "gphr/core/Error.hpp"
#include "gphr/core/Progress.hpp"
#include "gphr/offline/PodCheckpoint.hpp"

namespace gphr {

namespace {

ReducedBasis readBasis(const Hdf5File& f, const PhaseSpace& space) {
  ReducedBasis b;
  b.A = f.readStates("/basis", space);  // stored as rows: (2k, 2n) -> a MultiVector with 2k columns
  b.k = static_cast<int>(b.A->getNumVectors()) / 2;
  b.method = f.stringAttribute("/basis", "method");
  b.singularValues = f.doubleAttribute("/basis", "singularValues");
  b.energyCaptured = f.doubleAttribute("/basis", "energyCaptured")[0];
  return b;
}

void writeBasis(const ArtifactsCache& cache, Hdf5File& f, const ReducedBasis& b, const PhaseSpace& space,
                const std::string& sceneName, const TrainingResult& training, const std::string& key) {
  ArtifactsCache::clear(f, "/basis");
  f.writeStates("/basis", *b.A, space);
  ArtifactsCache::stampFingerprint(f, "/basis", columnFingerprint(*b.A));
  f.setAttribute("/basis", "method", b.method);
  f.setAttribute("/basis", "k", std::vector<double>{double(b.k)});
  f.setAttribute("/basis", "singularValues", b.singularValues);
  f.setAttribute("/basis", "energyCaptured", std::vector<double>{b.energyCaptured});
  f.setAttribute("/basis", "scene", sceneName);
  std::vector<double> flat;
  for (const auto& mu : training.parameters) flat.insert(flat.end(), mu.begin(), mu.end());
  f.setAttribute("/basis", "trainingSet", flat);
  f.setAttribute("/basis", "layout", std::string("rows are the 2k columns of A (2n entries each, global-id order)"));
  cache.seal(f, "/basis", key);
}

}  // namespace

void checkBasisSizeBeforeTraining(const TrainingOptions& t, const BasisOptions& options, int k, GO fullDim) {
  const long states = t.snapshotEvery >= 1 ? t.steps / t.snapshotEvery + 1 : 0;
  const long snapshots = static_cast<long>(t.parameters.size()) * states;
  if (fullDim <= 0 || k <= 0 || snapshots <= 0) return;
  const long bound = basisRankBound(options, fullDim / 2, snapshots);
  GPHR_REQUIRE(k <= bound, InputError, "k = ", k, " cannot come from the training: ", t.parameters.size(),
               " parameter(s) x ", states, " states give a ", options.method, " basis of at most k = ", bound,
               " on n = ", fullDim / 2, " dofs; allowed: k <= ", bound,
               ", or more training states (training.points, time.T / time.dt, training.snapshotEvery)");
}

BasisStageResult runBasisStage(const TrainingResult& training, const PhaseSpace& space, const BasisOptions& options,
                               const std::string& sceneName, const ArtifactsCache* cache, const std::string& key) {
  Teuchos::Time clock("basis");
  clock.start();
  const std::clock_t cpu0 = std::clock();
  BasisStageResult out;
  if (cache) {  // the file is closed while the basis is computed: the snapshots stream from it
    const auto f = cache->open();
    if (ArtifactsCache::holds(*f, "/basis", key)) {
      out.basis = readBasis(*f, space);
      // a basis that no longer matches its fingerprint (a changed value) is computed again
      const std::string problem = ArtifactsCache::fingerprintProblem(*f, "/basis", *out.basis.A);
      out.cached = problem.empty();
      if (!out.cached && space.comm()->getRank() == 0)
        std::fprintf(stderr, "[gphr] basis: /basis in '%s' %s: computed afresh\n", cache->path().c_str(),
                     problem.c_str());
    }
    if (out.cached) {
      PodCheckpoint(cache, "/basis", key).clear();  // a leftover of another run's basis, if any
      GPHR_REQUIRE(options.k == 0 || options.k == out.basis.k, InputError, "basis in '", cache->path(), "' has k = ",
                   out.basis.k, " but the config asks for k = ", options.k);
    }
  }
  if (!out.cached) {
    // Checkpoints after a training parameter's block, at most every cache->checkpointSeconds()
    // (PodCheckpoint.hpp): a restart goes on from the furthest, bit for bit. The key is the
    // basis's: it names the training and the options.
    PodCheckpoint checkpoint(cache, "/basis", key, &space);
    BasisProgress resume;
    const int count = static_cast<int>(training.snapshots.size());
    const PodProgress at = checkpoint.read(basisPodMap(space, options), 1, count, resume.pod);
    resume.blocks = static_cast<size_t>(at.progress);
    if (at.progress > 0) {
      resume.energy = at.extra[0];
      if (space.comm()->getRank() == 0)
        std::fprintf(stderr, "[gphr] basis: parameters 1-%d of %d reused from file\n", at.progress, count);
    }
    const auto save = [&](const BasisProgress& b) {  // the line after the checkpoint: "checkpointed" is kept
      const bool kept = checkpoint.write(b.pod, PodProgress{static_cast<int>(b.blocks), {b.energy}});
      if (space.comm()->getRank() == 0)
        progressLine("[gphr] basis: parameter %zu of %d POD'd, %.1f s%s", b.blocks, count, clock.totalElapsedTime(true),
                     kept ? ", checkpointed" : "");
    };
    out.basis = computeSymplecticBasis(training.snapshots, space, options, &resume, save);
    // save() runs between parameters only (the last one's POD is the basis, written next): the
    // sequence of lines ends at count of count here.
    if (space.comm()->getRank() == 0 && resume.blocks < static_cast<size_t>(count))
      progressLine("[gphr] basis: parameter %d of %d POD'd, %.1f s", count, count, clock.totalElapsedTime(true));
    if (cache) {
      writeBasis(*cache, *cache->open(), out.basis, space, sceneName, training, key);
      checkpoint.clear();  // their work is in the basis now
    }
  }
  out.seconds = clock.stop();
  out.cpuSeconds = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  return out;
}

}  // namespace gphr
