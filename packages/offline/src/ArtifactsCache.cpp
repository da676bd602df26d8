#include "gphr/offline/ArtifactsCache.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <cmath>
#include <filesystem>

#include "gphr/core/ColumnFingerprint.hpp"
#include "gphr/core/Error.hpp"

namespace gphr {

namespace {
// Removes the checkpoint files beside `path` (PodCheckpoint::path(): PATH.ckpt_NAME). They hold
// PODs of an artifacts file's snapshots; once that file is gone (the way to start afresh), a
// checkpoint under the same configuration key could hold a POD of other snapshots (a changed
// scene code, say) that its own fingerprint would not reveal.
void removeCheckpoints(const std::filesystem::path& path) {
  const std::string prefix = path.filename().string() + ".ckpt";
  const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
    if (entry.path().filename().string().rfind(prefix, 0) == 0) std::filesystem::remove(entry.path(), ec);
}
}  // namespace

ArtifactsCache::ArtifactsCache(std::string path, RCP<const Comm> comm, const std::string& sceneName, long fullDim)
    : path_(std::move(path)), comm_(std::move(comm)) {
  // Rank 0 looks and decides for all: ranks that disagreed (a network file system's attribute
  // cache) would open the file in two modes.
  int fresh = comm_->getRank() == 0 && !std::filesystem::exists(path_);
  Teuchos::broadcast(*comm_, 0, Teuchos::outArg(fresh));
  if (fresh) {
    if (comm_->getRank() == 0) removeCheckpoints(path_);
    Hdf5File f(path_, comm_, Hdf5File::Mode::Create);
    f.setAttribute("/", "scene", sceneName);
    f.setAttribute("/", "fullDim", std::vector<double>{double(fullDim)});
    return;
  }
  Hdf5File f(path_, comm_, Hdf5File::Mode::ReadWrite);
  const std::string scene = f.hasAttribute("/", "scene") ? f.stringAttribute("/", "scene") : "";
  GPHR_REQUIRE(scene == sceneName, InputError, "artifacts file '", path_, "' belongs to scene '", scene,
               "' but the config runs '", sceneName, "' (use another --output directory)");
  if (f.hasAttribute("/", "fullDim")) {
    const double nd = f.doubleAttribute("/", "fullDim")[0];
    GPHR_REQUIRE(nd == fullDim, InputError, "artifacts file '", path_, "' holds states of size ", nd,
                 " but the config gives size ", fullDim, " (use another --output directory)");
  } else {
    f.setAttribute("/", "fullDim", std::vector<double>{double(fullDim)});
  }
}

std::unique_ptr<Hdf5File> ArtifactsCache::open() const {
  return std::make_unique<Hdf5File>(path_, comm_, Hdf5File::Mode::ReadWrite);
}

bool ArtifactsCache::holds(const Hdf5File& file, const std::string& name, const std::string& key) {
  try {
    return file.hasAttribute(name, "complete") && file.hasAttribute(name, "config") &&
           file.stringAttribute(name, "config") == key;
  } catch (const InputError& e) {
    // A header HDF5 cannot read (its checksum) cannot be unlinked either (unlinking rewrites it):
    // say how to start afresh.
    throw InputError(detail::concat(e.what(), "; the artifacts file is damaged: remove '", file.path(),
                                    "' (or use another --output directory) to compute afresh"));
  }
}

void ArtifactsCache::seal(Hdf5File& file, const std::string& name, const std::string& key) const {
  seal(file, std::vector<std::string>{name}, key);
}

// The marks are set after the data were written (see the declaration): with syncToDisk() the data
// also reach the disk first, and a machine crash may lose marks, never leave one on missing data.
void ArtifactsCache::seal(Hdf5File& file, const std::vector<std::string>& names, const std::string& key) const {
  if (syncToDisk_) file.flush();
  else file.startWriteback();  // written while the next stage computes, not at a later fsync
  for (const std::string& name : names) {
    file.setAttribute(name, "config", key);
    file.setAttribute(name, "complete", std::string("yes"));
  }
}

void ArtifactsCache::stampFingerprint(Hdf5File& file, const std::string& name, const std::vector<double>& fingerprint) {
  file.setAttribute(name, "fingerprint", fingerprint);
}

std::string ArtifactsCache::fingerprintProblem(const Hdf5File& file, const std::string& name, const MultiVector& X,
                                               size_t every, size_t first) {
  if (!file.hasAttribute(name, "fingerprint")) return "has no fingerprint (written by an older gphr)";
  const std::vector<double> stored = file.doubleAttribute(name, "fingerprint");
  std::vector<double> read(X.getNumVectors(), NAN);  // the stored entries of the columns read; NaN past the end
  for (size_t i = 0; i < read.size(); ++i)
    if ((first + i) * every < stored.size()) read[i] = stored[(first + i) * every];
  const long bad = firstMismatchingColumn(read, X);
  if (bad < 0) return "";
  return detail::concat("column ", (first + static_cast<size_t>(bad)) * every, " does not match its fingerprint");
}

void ArtifactsCache::clear(Hdf5File& file, const std::string& name) {
  file.remove(name);
  // the parent groups, outermost first ("/deim/k10" needs "/deim")
  for (size_t slash = name.find('/', 1); slash != std::string::npos; slash = name.find('/', slash + 1))
    if (!file.exists(name.substr(0, slash))) file.createGroup(name.substr(0, slash));
}

void ArtifactsCache::setCheckpointSeconds(double seconds) {
  GPHR_REQUIRE(seconds >= 0.0 && seconds < 1e9, InputError, "checkpoint interval ", seconds,
               " s; allowed: 0 (after every block) to 1e9 seconds");
  checkpointSeconds_ = seconds;
}

}  // namespace gphr
