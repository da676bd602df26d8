#pragma once
/// @file
/// The offline phase as one sequence of stages, the same for `gphr run`, `gphr build` and a
/// user's code (examples/embedding): training, the scene's instance, the symplectic basis, then per
/// reduced size k the DEIM basis and the term-weight fits. A stage runs on its first request, in
/// that order whatever asks first, through the artifacts cache under its own key: each stage's
/// key is written by its options' package from the options and the algorithm's revision
/// (trainingCacheKey, basisCacheKey, deimBasisCacheKey, quadratureCacheKey; core/CacheKey.hpp),
/// each one after the keys of the stages it depends on. Every stage is timed in clocks() and
/// reported to the stage hook as it ends (progress for a caller that wants its own).
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gphr/core/StageClock.hpp"
#include "gphr/hyper/DeimBasis.hpp"
#include "gphr/hyper/EmpiricalQuadrature.hpp"
#include "gphr/offline/BasisStage.hpp"
#include "gphr/offline/DeimBasisStage.hpp"
#include "gphr/offline/TermWeightFits.hpp"
#include "gphr/offline/Training.hpp"

namespace gphr {

/// The DEIM sizes of reduced size k: byK's list where it has k, else `ms` (every other k's).
const std::vector<int>& deimSizesOf(const std::vector<int>& ms, const std::map<int, std::vector<int>>& byK, int k);
/// Every m of `ms` and of byK's lists, ascending, each once.
std::vector<int> allDeimSizes(const std::vector<int>& ms, const std::map<int, std::vector<int>>& byK);

/// What the offline stages compute.
struct OfflineOptions {
  TrainingOptions training;   ///< the training set and its time integration
  BasisOptions basis;         ///< the symplectic basis; k: the largest of `ks` (0: by the energy tolerance)
  std::vector<int> ks;        ///< the reduced sizes (leading parts of the basis); empty: the basis's k
  std::vector<int> ms;        ///< DEIM sizes m and term budgets (of every k not in msByK)
  std::map<int, std::vector<int>> msByK;  ///< a k's own DEIM sizes and budgets, in place of ms
  /// The DEIM sizes and budgets of reduced size k: msByK's where it has k, else ms.
  const std::vector<int>& msOf(int k) const { return deimSizesOf(ms, msByK, k); }
  /// Every m of any k (ms and msByK's), ascending, each once.
  std::vector<int> allMs() const { return allDeimSizes(ms, msByK); }
  DeimBasisOptions deim;      ///< the DEIM basis (maxRank 0: the largest m + kDeimRankMargin)
  QuadratureOptions eqp;      ///< the term-weight fits' training system
  double eqpTolerance = 1e-8; ///< NNLS stopping tolerance (relative residual)
  /// The scene's configuration as text: its identity in the cache keys (and a model file's
  /// provenance). Empty: the scene's name stands for it, which is enough without a cache.
  std::string sceneConfig;
};

/// The stages' cache keys: prefixes that the DEIM basis and fit stages complete with k (and m).
struct OfflineKeys {
  std::string training;  ///< of the training set (its parameters included): what the later stages' keys begin with
  std::string trainingStates;  ///< of the training's states in the cache (trainingStatesKey: each kept with its parameter)
  std::string basis;     ///< of the basis (the training's key first)
  std::string deim;      ///< of the DEIM bases (the basis's key first)
  std::string nnls;      ///< of the gp-eqp fits (the basis's key first)
};

/// The keys of `options`' stages for `scene`.
OfflineKeys offlineKeys(const Scene& scene, const OfflineOptions& options);

/// A stage as it ended: its name (as in clocks()), wall seconds, and whether the cache held it.
struct OfflineStageEnd {
  std::string name;      ///< "training", "instance", "basis", "deim basis k=K"
  double seconds = 0.0;  ///< wall seconds of the stage on this rank
  bool cached = false;   ///< taken from the artifacts cache (the training: every parameter)
};

/// The offline stages of one scene (see the file's description). Collective over `comm`: every
/// rank asks for the same stages in the same order.
class OfflineSequence {
 public:
  /// What a caller is told as each stage ends.
  using StageHook = std::function<void(const OfflineStageEnd&)>;
  /// mu: the instance whose row maps and sample meshes the stages use (empty: the box's centre).
  /// With `cache` (copied), every stage reuses what it holds for its key.
  OfflineSequence(const Scene& scene, RCP<const Comm> comm, OfflineOptions options, std::vector<double> mu = {},
                  const ArtifactsCache* cache = nullptr);
  ~OfflineSequence();
  OfflineSequence(const OfflineSequence&) = delete;
  OfflineSequence& operator=(const OfflineSequence&) = delete;

  /// Sets the cache of the stages not run yet (one that needs the instance's size to open it).
  void setCache(const ArtifactsCache& cache) { cache_ = std::make_unique<ArtifactsCache>(cache); }
  /// Called as each stage ends (after its clock stops).
  void setStageHook(StageHook hook) { hook_ = std::move(hook); }
  const OfflineOptions& options() const { return options_; }  ///< as given, DEIM's largestM filled in
  const OfflineKeys& keys() const { return keys_; }           ///< the stages' cache keys
  const Scene& scene() const { return scene_; }               ///< the scene
  const RCP<const Comm>& comm() const { return comm_; }       ///< the communicator of every stage
  /// The clocks of the stages so far ("training", "instance", "basis", "deim basis k=K", "fits k=K");
  /// a caller adds stages of its own (StageClocks::Scope).
  StageClocks& clocks() { return clocks_; }

  const TrainingResult& training();    ///< the training stage
  const SceneInstance& instance();     ///< the shifted instance at mu
  const BasisStageResult& basis();     ///< the basis stage (after the training)
  /// The reduced sizes asked for (OfflineOptions::ks, empty: the basis's k), checked against the basis.
  std::vector<int> sizes();
  /// The leading 2k columns of the basis.
  RCP<const MultiVector> reducedBasis(int k);
  /// The DEIM basis of size k. The latest k's is held (a request for another k replaces it), so a
  /// second request of the same k costs nothing and reports the first one's `cached`.
  const CachedDeimBasis& deimBasis(int k);
  /// The term-weight fits of size k, gp-eqp-refit's terms by the DEIM index rule `indices` (deim |
  /// qdeim) on deimBasis(k). The latest k's are held.
  TermWeightFits& termWeightFits(int k, const std::string& indices);

 private:
  void ended(const std::string& stage, double seconds, bool cached);

  const Scene& scene_;
  RCP<const Comm> comm_;
  OfflineOptions options_;
  std::vector<double> mu_;
  std::unique_ptr<ArtifactsCache> cache_;
  OfflineKeys keys_;
  StageClocks clocks_;
  StageHook hook_;
  std::unique_ptr<TrainingResult> training_;
  std::unique_ptr<SceneInstance> instance_;
  std::unique_ptr<BasisStageResult> basis_;
  std::map<int, RCP<const MultiVector>> reduced_;
  int deimK_ = -1;
  std::unique_ptr<CachedDeimBasis> deim_;
  int fitsK_ = -1;
  std::string fitsIndices_;
  std::unique_ptr<TermWeightFits> fits_;
};

}  // namespace gphr
