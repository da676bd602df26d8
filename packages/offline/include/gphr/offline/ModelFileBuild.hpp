#pragma once
/// @file
/// The whole offline phase of a scene in one call, what `gphr build` runs and what a code with
/// a Hamiltonian of its own calls (examples/embedding): training, the symplectic basis, per
/// reduced size k the DEIM basis and the term-weight fits of the stored methods, then the
/// reduced-model file (doc/model-file.md) that ReducedModel (packages/online) loads.
#include <map>
#include <string>
#include <vector>

#include "gphr/core/StageClock.hpp"
#include "gphr/hyper/GpAdeimModel.hpp"
#include "gphr/offline/ErrorCalibration.hpp"
#include "gphr/offline/ModelFileBuilder.hpp"
#include "gphr/offline/OfflineSequence.hpp"

namespace gphr {

/// What the offline phase computes and stores: the stages' options (OfflineSequence.hpp) and the file's.
struct ModelBuildOptions : OfflineOptions {
  std::vector<std::string> methods{"gp-deim"};  ///< the storable methods to store (core/Method.hpp)
  AdeimOptions adeim;         ///< gp-adeim's options, stored with each of its models
  bool withBasis = true;      ///< store A (gp-adeim queries and the exact set-up route need it)
  ModelFileOptions file;      ///< probes, interpolation nodes, DEIM indices, the integrator section
  std::vector<double> parameter;  ///< the instance that supplies the stored sample meshes (empty: the box's centre)
  double T = 0.0;             ///< the file's default horizon (0: the training's steps x dt)
  std::string config;         ///< provenance: the whole configuration as YAML
  std::vector<TrainingRound> greedyRounds;  ///< provenance: the greedy training's rounds (GreedyTraining.hpp)
  std::vector<QueryDefault> queryDefaults;  ///< the file's query defaults (the greedy training's choice)
  /// Provenance: wall seconds of the offline work before this build (a greedy training's earlier
  /// rounds and its confirmations), added to the file's offline seconds: its break-even counts them.
  double earlierSeconds = 0.0;
};

/// What the offline phase produced.
struct ModelBuildResult {
  ReducedModelData data;   ///< the file's contents (bases not included)
  TrainingResult training; ///< the training stage
  BasisStageResult basis;  ///< the basis stage
  double seconds = 0.0;    ///< wall seconds of the whole phase, the file's write included
  /// This rank's clocks per stage (StageClock.hpp), in order: "training", "instance", "basis",
  /// "header", per k "deim basis k=K", "gp-deim k=K" (DEIM indices and sample meshes), "fits k=K"
  /// (term-weight fits, gp-eqp), "interpolation k=K" (the parameter interpolants of the basis
  /// data), "calibration" (the error indicators, ErrorCalibration.hpp), then "write" (the model file). Stages not run are absent; they add up to the phase.
  std::vector<StageTime> stages;
  /// What could not be built and is not in the file, one line each ("gp-deim k = 10, m = 120: the
  /// DEIM basis has 91 vectors ..."; a k with no model at all is left out too), as `gphr run`
  /// marks such a run unavailable; also said on stderr by rank 0 as it happens.
  std::vector<std::string> skipped;
  /// Per model key, the training points its error indicator was calibrated on (ErrorCalibration.hpp).
  std::map<std::string, std::vector<CalibrationPoint>> calibration;
};

/// Checks `options` for `scene` before any work: the methods, sizes and parameter, gp-adeim alone
/// where it cannot be stored, and (fullDim > 0, the scene's state size 2n) the probes. InputError
/// naming the value. buildReducedModelFile checks the same (but the probes) itself.
void checkModelBuildOptions(const Scene& scene, const ModelBuildOptions& options, GO fullDim = 0);

/// Runs the offline phase for `scene` and writes the reduced-model file at `path` (write-then-
/// rename): the stages of an OfflineSequence, then per k the stored models, the parameter
/// interpolants and the file. A model that cannot be built is left out and named
/// (ModelBuildResult::skipped); InputError when none can. With `cache`, every stage reuses what it holds for its key.
/// `hook`: called as each stage of the sequence ends. Collective over `comm`.
ModelBuildResult buildReducedModelFile(const Scene& scene, const RCP<const Comm>& comm,
                                       const ModelBuildOptions& options, const std::string& path,
                                       const ArtifactsCache* cache = nullptr,
                                       const OfflineSequence::StageHook& hook = {});

}  // namespace gphr
