#include "gphr/offline/DeimBasisStage.hpp"

#include <Teuchos_Time.hpp>
#include <cmath>
#include <cstdio>

#include "gphr/core/Error.hpp"

namespace gphr {

namespace {

bool readDeimBasis(const Hdf5File& f, const std::string& name, const std::string& key,
                   const HamiltonianSystem& reference, CachedDeimBasis& out) {
  if (!ArtifactsCache::holds(f, name, key)) return false;
  out.basis.U = f.readColumns(name, reference.nonlinearTerm().rowMap());
  out.basis.singularValues = f.doubleAttribute(name, "singularValues");
  out.basis.snapshots = static_cast<long>(f.doubleAttribute(name, "snapshots")[0]);
  out.computeSeconds = f.hasAttribute(name, "seconds") ? f.doubleAttribute(name, "seconds")[0] : NAN;
  out.cached = true;
  return true;
}

void writeDeimBasis(Hdf5File& f, const std::string& name, const std::string& key, const CachedDeimBasis& d) {
  ArtifactsCache::clear(f, name);
  f.writeColumns(name, *d.basis.U);
  f.setAttribute(name, "singularValues", d.basis.singularValues);
  f.setAttribute(name, "snapshots", std::vector<double>{double(d.basis.snapshots)});
  f.setAttribute(name, "seconds", std::vector<double>{d.computeSeconds});
  f.setAttribute(name, "layout", std::string("rows are the DEIM basis vectors U (d entries each, row-of-G order)"));
  ArtifactsCache::seal(f, name, key);
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
  if (!out.cached) {
    try {
      out.basis = computeDeimBasis(trainingSystems(scene, comm, training), training.snapshots, A, options);
    } catch (const InputError& e) {  // e.g. podRoute 'tsqr' on too few rows per rank: name the section
      throw InputError(detail::concat(section, ": ", e.what()));
    }
    out.computeSeconds = clock.totalElapsedTime(true);
    if (cache) writeDeimBasis(*cache->open(), name, fullKey, out);
  }
  out.seconds = clock.stop();
  if (comm->getRank() == 0)
    std::fprintf(stderr, "[gphr] deim basis k = %d: %zu vectors from %ld snapshots%s, %.1f s\n", k,
                 out.basis.singularValues.size(), out.basis.snapshots, out.cached ? " (cached)" : "", out.seconds);
  return out;
}

}  // namespace gphr
