#include "gphr/offline/OfflineSequence.hpp"

#include <Teuchos_Time.hpp>
#include <algorithm>

#include "gphr/core/Error.hpp"
#include "gphr/reduction/Deim.hpp"

namespace gphr {

namespace {

std::string ofK(const char* stage, int k) { return std::string(stage) + " k=" + std::to_string(k); }

std::vector<double> boxCentre(const ParameterBox& box) {
  std::vector<double> c;
  for (const auto& [lo, hi] : box.bounds) c.push_back(0.5 * (lo + hi));
  return c;
}

// The DEIM basis keeps room for the largest m asked for (deimMaxRank) unless told otherwise.
OfflineOptions completed(OfflineOptions o) {
  const auto all = o.allMs();
  if (o.deim.largestM == 0 && !all.empty()) o.deim.largestM = all.back();
  return o;
}

}  // namespace

const std::vector<int>& deimSizesOf(const std::vector<int>& ms, const std::map<int, std::vector<int>>& byK, int k) {
  const auto it = byK.find(k);
  return it == byK.end() ? ms : it->second;
}

std::vector<int> allDeimSizes(const std::vector<int>& ms, const std::map<int, std::vector<int>>& byK) {
  std::vector<int> all = ms;
  for (const auto& [k, list] : byK) all.insert(all.end(), list.begin(), list.end());
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  return all;
}

OfflineKeys offlineKeys(const Scene& scene, const OfflineOptions& o) {
  OfflineKeys k;
  const std::string sceneConfig = o.sceneConfig.empty() ? "name: " + scene.name() : o.sceneConfig;
  k.training = trainingCacheKey(sceneConfig, o.training);
  k.trainingStates = trainingStatesKey(sceneConfig, o.training);
  k.basis = k.training + basisCacheKey(o.basis);
  k.deim = k.basis + deimBasisCacheKey(completed(o).deim);
  k.nnls = k.basis + quadratureCacheKey(o.eqp, o.eqpTolerance);
  return k;
}

OfflineSequence::OfflineSequence(const Scene& scene, RCP<const Comm> comm, OfflineOptions options,
                                 std::vector<double> mu, const ArtifactsCache* cache)
    : scene_(scene), comm_(std::move(comm)), options_(completed(std::move(options))),
      mu_(mu.empty() ? boxCentre(scene.parameterBox()) : std::move(mu)), keys_(offlineKeys(scene, options_)) {
  if (cache) cache_ = std::make_unique<ArtifactsCache>(*cache);
}

OfflineSequence::~OfflineSequence() = default;

void OfflineSequence::ended(const std::string& stage, double seconds, bool cached) {
  if (hook_) hook_({stage, seconds, cached});
}

const TrainingResult& OfflineSequence::training() {
  if (!training_) {
    {
      const StageClocks::Scope clock(clocks_, "training");
      training_ = std::make_unique<TrainingResult>(runTraining(scene_, comm_, options_.training, cache_.get(), keys_.trainingStates));
    }
    ended("training", training_->seconds, training_->reused == static_cast<long>(training_->parameters.size()));
  }
  return *training_;
}

const SceneInstance& OfflineSequence::instance() {
  if (!instance_) {
    Teuchos::Time clock("instance");
    clock.start();
    {
      const StageClocks::Scope stage(clocks_, "instance");
      instance_ = std::make_unique<SceneInstance>(scene_.instantiate(comm_, mu_, true));
    }
    ended("instance", clock.stop(), false);
  }
  return *instance_;
}

const BasisStageResult& OfflineSequence::basis() {
  if (!basis_) {
    const TrainingResult& snapshots = training();
    const PhaseSpace& space = instance().system->space();
    {
      const StageClocks::Scope clock(clocks_, "basis");
      basis_ = std::make_unique<BasisStageResult>(
          runBasisStage(snapshots, space, options_.basis, scene_.name(), cache_.get(), keys_.basis));
    }
    ended("basis", basis_->seconds, basis_->cached);
  }
  return *basis_;
}

std::vector<int> OfflineSequence::sizes() {
  return basisSizes(options_.ks.empty() ? std::vector<int>{0} : options_.ks, basis().basis);
}

RCP<const MultiVector> OfflineSequence::reducedBasis(int k) {
  auto it = reduced_.find(k);
  if (it == reduced_.end()) it = reduced_.emplace(k, leadingBasis(basis().basis, k)).first;
  return it->second;
}

const CachedDeimBasis& OfflineSequence::deimBasis(int k) {
  if (!deim_ || deimK_ != k) {
    const auto A = reducedBasis(k);
    const TrainingResult& snapshots = training();
    const HamiltonianSystem& system = *instance().system;
    deim_.reset();  // the previous k's basis is released before this one is made
    {
      const StageClocks::Scope clock(clocks_, ofK("deim basis", k));
      deim_ = std::make_unique<CachedDeimBasis>(
          runDeimBasisStage(scene_, comm_, snapshots, *A, system, options_.deim, cache_.get(), keys_.deim));
    }
    deimK_ = k;
    ended(ofK("deim basis", k), deim_->seconds, deim_->cached);
  }
  return *deim_;
}

TermWeightFits& OfflineSequence::termWeightFits(int k, const std::string& indices) {
  if (!fits_ || fitsK_ != k || fitsIndices_ != indices) {
    const auto A = reducedBasis(k);
    // GP-DEIM's terms for the refit, asked only when a refit is not in the cache.
    auto deimTerms = [this, k, indices](int m) {
      const auto& U = *deimBasis(k).basis.U;
      GPHR_REQUIRE(m <= static_cast<int>(U.getNumVectors()), InputError, "the DEIM basis has ", U.getNumVectors(),
                   " vectors, m = ", m);
      return selectDeimIndices(U, m, indices);
    };
    // The refit's terms are GP-DEIM's: its key is the fit's, the DEIM basis's and the index rule.
    const std::string refitKey = keys_.nnls + keys_.deim + "indices = " + indices + "\n";
    fits_.reset();
    fits_ = std::make_unique<TermWeightFits>(scene_, comm_, training(), *A, options_.eqp, options_.eqpTolerance,
                                             options_.msOf(k), deimTerms, cache_.get(), keys_.nnls, refitKey);
    fitsK_ = k, fitsIndices_ = indices;
  }
  return *fits_;
}

}  // namespace gphr
