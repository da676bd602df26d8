#include "gphr/offline/PodCheckpoint.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <cstdio>
#include <filesystem>
#include <memory>

#include "gphr/core/ColumnFingerprint.hpp"
#include "gphr/core/Error.hpp"

namespace gphr {

PodCheckpoint::PodCheckpoint(const ArtifactsCache* cache, std::string name, std::string key, const PhaseSpace* space)
    : cache_(cache), name_(std::move(name)), key_(std::move(key)), space_(space) {
  sinceWrite_.start();
}

std::string PodCheckpoint::path() const {
  std::string tail = name_;
  for (char& c : tail) c = c == '/' ? '_' : c;
  return cache_->path() + ".ckpt" + tail;
}

bool PodCheckpoint::exists() const {
  int there = cache_->comm()->getRank() == 0 && std::filesystem::exists(path());
  Teuchos::broadcast(*cache_->comm(), 0, Teuchos::outArg(there));
  return there != 0;
}

namespace {
constexpr size_t kFigures = 2 + PodSteps::kFields;  // the "pod" attribute: energy, columns, steps by route

// Whether vectors on `map` go to the file as states of `space` (else as columns of a contiguous map).
bool asStates(const Map& map, const PhaseSpace* space) {
  if (map.isContiguous()) return false;
  GPHR_REQUIRE(space && map.isSameAs(*space->map()), InputError,
               "POD checkpoint: the POD's map is neither contiguous nor the phase space's state map");
  return true;
}
}  // namespace

bool PodCheckpoint::write(const StreamingPod::State& pod, const PodProgress& at) {
  if (!cache_) return false;
  int due = sinceWrite_.totalElapsedTime(true) >= cache_->checkpointSeconds();
  Teuchos::broadcast(*cache_->comm(), 0, Teuchos::outArg(due));  // every rank writes, or none
  if (!due) return false;
  // a file that could not be read (a kill while it was first created, say) is made anew
  const auto f = std::make_unique<Hdf5File>(path(), cache_->comm(),
                                            exists() && !unreadable_ ? Hdf5File::Mode::ReadWrite : Hdf5File::Mode::Create);
  unreadable_ = false;
  const std::string name = slot(next_);
  ArtifactsCache::clear(*f, name);
  if (asStates(*pod.U->getMap(), space_)) f->writeStates(name, *pod.U, *space_);
  else f->writeColumns(name, *pod.U);
  ArtifactsCache::stampFingerprint(*f, name, columnFingerprint(*pod.U));
  f->setAttribute(name, "singularValues", pod.sigma);
  std::vector<double> figures{pod.energy, double(pod.columns)};  // then the steps by route
  figures.resize(kFigures);
  pod.steps.put(figures.data() + 2);
  f->setAttribute(name, "pod", figures);
  f->setAttribute(name, "progress", std::vector<double>{double(at.progress)});
  f->setAttribute(name, "extra", at.extra);
  cache_->seal(*f, name, key_);
  next_ = 1 - next_;
  sinceWrite_.reset();
  sinceWrite_.start();
  return true;
}

PodProgress PodCheckpoint::read(const RCP<const Map>& map, size_t extraSize, int limit, StreamingPod::State& pod) {
  if (!cache_ || !exists()) return PodProgress();
  try {
    const Hdf5File f(path(), cache_->comm(), Hdf5File::Mode::ReadOnly);
    PodProgress at;
    int best = -1;
    for (int i = 0; i < 2; ++i) {
      if (!ArtifactsCache::holds(f, slot(i), key_)) continue;
      const int progress = static_cast<int>(f.doubleAttribute(slot(i), "progress").at(0));
      if (progress > at.progress && progress < limit) best = i, at.progress = progress;
    }
    if (best < 0) return PodProgress();
    const std::string name = slot(best);
    const auto figures = f.doubleAttribute(name, "pod");
    at.extra = f.doubleAttribute(name, "extra");
    GPHR_REQUIRE(figures.size() == kFigures && at.extra.size() == extraSize, InputError, name, " holds ",
                 figures.size(), " POD and ", at.extra.size(), " stage figures (allowed: ", kFigures, " and ",
                 extraSize, ")");
    pod.U = asStates(*map, space_) ? f.readStates(name, *space_) : f.readColumns(name, map);
    const std::string problem = ArtifactsCache::fingerprintProblem(f, name, *pod.U);
    GPHR_REQUIRE(problem.empty(), InputError, name, " ", problem);  // a changed value: computed afresh (below)
    pod.sigma = f.doubleAttribute(name, "singularValues");
    pod.energy = figures[0], pod.columns = static_cast<long>(figures[1]);
    pod.steps = PodSteps::get(figures.data() + 2);
    next_ = 1 - best;  // keep the one restored until a newer one is complete
    return at;
  } catch (const std::exception& e) {  // a checkpoint saves time, never stops a run: computed afresh
    if (cache_->comm()->getRank() == 0)
      std::fprintf(stderr, "[gphr] %s: the checkpoint file '%s' is unreadable or damaged (%s): computed afresh\n",
                   name_.c_str(), path().c_str(), e.what());
    unreadable_ = true;
    return PodProgress();
  }
}

void PodCheckpoint::clear() const {
  if (!cache_) return;
  cache_->comm()->barrier();  // no rank has it open
  if (cache_->comm()->getRank() == 0) std::filesystem::remove(path());
  cache_->comm()->barrier();  // gone for every rank
}

}  // namespace gphr
