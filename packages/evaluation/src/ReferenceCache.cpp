#include "gphr/evaluation/ReferenceCache.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <cstdio>
#include <filesystem>
#include <memory>

#include "gphr/core/ColumnFingerprint.hpp"
#include "gphr/core/Error.hpp"
#include "gphr/core/Fnv1a.hpp"
#include "gphr/offline/ArtifactsCache.hpp"

namespace gphr {

namespace {
constexpr char kStates[] = "/fom/states", kHamiltonian[] = "/fom/hamiltonian";

// H is replicated on every rank: a checksum of its bytes (the states, distributed, carry a
// ColumnFingerprint instead).
std::string hamiltonianChecksum(const std::vector<double>& H) {
  Fnv1a h;
  h.numbers(H);
  return h.hex();
}

std::vector<double> statsOf(const FullModelReference& r) {
  const RunStats& s = r.stats;
  return {double(s.steps), double(s.newtonIterations), double(s.linearIterations), double(s.newtonMatrices),
          s.maxResidual, s.driftBound, s.wallSeconds, r.tOnline, r.driftBound};
}

void setStats(const std::vector<double>& v, FullModelReference& r) {
  GPHR_REQUIRE(v.size() == 9, InputError, "attribute 'run_stats' has ", v.size(), " entries; allowed: 9");
  RunStats& s = r.stats;
  s.steps = long(v[0]), s.newtonIterations = long(v[1]), s.linearIterations = long(v[2]), s.newtonMatrices = long(v[3]);
  s.maxResidual = v[4], s.driftBound = v[5], s.wallSeconds = v[6], r.tOnline = v[7], r.driftBound = v[8];
}

// The reference held under `key`, into `out`; false where the file holds none under this key.
// Data that do not match their fingerprint or checksum are an InputError (the file is replaced).
bool readReference(const ArtifactsCache& cache, const std::string& key, const PhaseSpace& space,
                   FullModelReference& out) {
  const auto f = cache.open();
  if (!ArtifactsCache::holds(*f, kStates, key) || !ArtifactsCache::holds(*f, kHamiltonian, key)) return false;
  out.trajectory = f->readStates(kStates, space);
  out.savedTimes = f->doubleAttribute(kStates, "saved_times");
  out.hamiltonian = f->readArray(kHamiltonian);
  setStats(f->doubleAttribute(kHamiltonian, "run_stats"), out);
  const std::string problem = ArtifactsCache::fingerprintProblem(*f, kStates, *out.trajectory);
  GPHR_REQUIRE(problem.empty(), InputError, "dataset ", kStates, " ", problem);
  GPHR_REQUIRE(f->stringAttribute(kHamiltonian, "checksum") == hamiltonianChecksum(out.hamiltonian), InputError,
               "dataset ", kHamiltonian, " does not match its checksum");
  return true;
}

void writeReference(const ArtifactsCache& cache, const std::string& key, const PhaseSpace& space,
                    const FullModelReference& ref) {
  const auto f = cache.open();
  ArtifactsCache::clear(*f, kStates);
  ArtifactsCache::clear(*f, kHamiltonian);
  f->writeStates(kStates, *ref.trajectory, space);
  ArtifactsCache::stampFingerprint(*f, kStates, columnFingerprint(*ref.trajectory));
  f->setAttribute(kStates, "saved_times", ref.savedTimes);
  f->writeArray(kHamiltonian, ref.hamiltonian, ref.hamiltonian.size(), 1);
  f->setAttribute(kHamiltonian, "checksum", hamiltonianChecksum(ref.hamiltonian));
  // The times are each rank's own: rank 0's are stored, so that every rank writes the same attribute.
  std::vector<double> stats = statsOf(ref);
  Teuchos::broadcast(*cache.comm(), 0, static_cast<int>(stats.size()), stats.data());
  f->setAttribute(kHamiltonian, "run_stats", stats);
  cache.seal(*f, std::vector<std::string>{kStates, kHamiltonian}, key);
}
}  // namespace

FullModelReference cachedFullModel(const std::string& path, const std::string& key, const EvaluationSettings& settings,
                                   const Scene& scene, const std::vector<double>& mu, const RCP<const Comm>& comm,
                                   bool* cached) {
  const auto inst = scene.instantiate(comm, mu, settings.shift);
  const PhaseSpace& space = inst.system->space();
  std::unique_ptr<ArtifactsCache> cache;
  FullModelReference ref;
  bool held = false;
  try {  // every rank reads the same file, so every rank fails alike
    cache = std::make_unique<ArtifactsCache>(path, comm, scene.name(), space.fullDim());
    held = readReference(*cache, key, space, ref);
  } catch (const InputError& e) {  // damaged (HDF5's header checksums, ours), another scene or size: replaced
    if (comm->getRank() == 0)
      std::fprintf(stderr, "[gphr] %s cannot be used (%s): the full model is run again and the file replaced\n",
                   path.c_str(), e.what());
    cache.reset();
    comm->barrier();
    if (comm->getRank() == 0) std::filesystem::remove(path);
    comm->barrier();
    cache = std::make_unique<ArtifactsCache>(path, comm, scene.name(), space.fullDim());
    ref = FullModelReference();
  }
  if (cached) *cached = held;
  if (held) {
    setSizes(*inst.system, ref);
    return ref;
  }
  ref = runFullModel(settings, scene, mu, comm);
  writeReference(*cache, key, space, ref);
  return ref;
}

}  // namespace gphr
