#pragma once
/// @file
/// The training stage: the full model of a scene integrated at each training parameter, its
/// shifted states y - y0(mu) kept every snapshotEvery-th step (the snapshots of the basis, the
/// DEIM basis and the term-weight fits). With an artifacts cache each parameter's snapshots are
/// written as soon as it finishes, so that a resumed run keeps every finished parameter.
#include <Teuchos_ParameterList.hpp>
#include <string>
#include <vector>

#include "gphr/core/SnapshotSet.hpp"
#include "gphr/core/SystemSet.hpp"
#include "gphr/models/Scene.hpp"
#include "gphr/offline/ArtifactsCache.hpp"

namespace gphr {

/// What the training stage integrates.
struct TrainingOptions {
  std::vector<std::vector<double>> parameters;  ///< the training parameters mu (each inside the box)
  double dt = 0.0;                              ///< time step
  long steps = 0;                               ///< steps per parameter
  long snapshotEvery = 1;                       ///< keep every snapshotEvery-th state (and state 0)
  Teuchos::ParameterList integrator{"integrator"};  ///< the integrator section (scheme, Newton)
  bool progress = true;                         ///< one progress line per parameter on rank 0 (stderr)
  /// Ranks per training group: the communicator splits into groups of this many consecutive ranks
  /// (the last may be larger), each integrating its own parameters (j = group, group + groups, ...)
  /// side by side; needs the artifacts cache (the snapshots meet there). 0: trainingGroupSize().
  int groupSize = 0;
};

/// The group size for `parameters` systems of fullDim state rows on `ranks` ranks: ranks / G for
/// the group count G with the least ceil(parameters / G) / floor(ranks / G) (rounds per rank of a
/// group; ties: more groups)
/// among those whose groups keep at least kTrainingRowsPerRank rows per rank (a smaller share is
/// mostly communication) and at most kMaxTrainingRowsPerRank (memory); 1 .. ranks.
int trainingGroupSize(long fullDim, int ranks, long parameters);
constexpr long kTrainingRowsPerRank = 4096;  ///< The fewest state rows per rank worth splitting a system over.
constexpr long kMaxTrainingRowsPerRank = 1L << 18;  ///< The most state rows per rank a group's system may put on one.

/// The options a `training` section sets (values or points, snapshotEvery, groupSize), the
/// parameters checked against `box`; the time step, steps and integrator are the caller's.
TrainingOptions trainingOptionsFrom(const Teuchos::ParameterList& training, const ParameterBox& box);
/// The training stage's cache key (core/CacheKey.hpp): the scene (`sceneConfig`, its configuration
/// as text: the scene's identity, which only the caller knows), the parameters, time step, steps,
/// snapshotEvery and integrator. groupSize and progress (who integrates what, and what is printed)
/// are left out: the snapshots are the same to round-off.
std::string trainingCacheKey(const std::string& sceneConfig, const TrainingOptions& options);
/// The key runTraining keeps the states under: trainingCacheKey without the parameters (the scene,
/// time step, steps, snapshotEvery, integrator). Each parameter's dataset is kept with its own
/// values, so that a set grown by a parameter trains that one only.
std::string trainingStatesKey(const std::string& sceneConfig, const TrainingOptions& options);
/// The keys of a `training` section with their defaults, ranges and documentation, for a box of
/// `parameters` parameters (the default grid: 3 points each).
Teuchos::ParameterList trainingValidParameters(size_t parameters);

/// The tensor grid over `box` with points[i] equispaced values of parameter i (1: its midpoint),
/// the first parameter fastest. InputError unless there is one count per parameter, each in [1, 10000].
std::vector<std::vector<double>> trainingGrid(const ParameterBox& box, const std::vector<int>& points);

/// The training stage's results: the training parameters and their shifted snapshots.
struct TrainingResult {
  std::vector<std::vector<double>> parameters;  ///< The training parameters mu.
  /// Shifted states per training parameter: streamed from the artifacts cache when there is one
  /// (a block read per access, so the stages after training hold one parameter's states at a
  /// time), else held in memory.
  SnapshotSet snapshots;
  long reused = 0;                                ///< parameters taken from the cache
  /// Ranks per rank group of the training (TrainingOptions::groupSize, resolved; the DEIM basis
  /// stage chooses its own groups). 0 when the snapshots are held in memory (no groups).
  int groupSize = 0;
  /// Rounds of integration with the cache: in each, every rank group integrates one parameter the
  /// cache lacked, side by side (ceil of the most any group has to train). 0 when held in memory.
  long rounds = 0;
  std::string cachePath;                          ///< the artifacts file the snapshots stream from ("": held)
  double seconds = 0.0;                           ///< Wall seconds of the stage.
};

/// Integrates the scene at every training parameter. With `cache`, each parameter's snapshots are
/// written to it while they are integrated, kSnapshotReadColumns states at a time, so the training
/// holds one such block per rank however long the trajectory; the result streams them from the
/// file. A parameter whose dataset is complete for `key` (trainingStatesKey) and holds its values
/// is not integrated again -- so a grown set integrates its new parameters only --, one without its
/// mark (killed mid-way) or of other values is redone, and a cache trained with another key is
/// trained again. With a
/// cache the ranks train in groups (TrainingOptions::groupSize), a round of parameters side by
/// side, each group's ranks writing their own rows of its parameter (Hdf5File::writeStateRows).
/// Collective over `comm`.
TrainingResult runTraining(const Scene& scene, const RCP<const Comm>& comm, const TrainingOptions& options,
                           const ArtifactsCache* cache = nullptr, const std::string& key = "");

/// The training's snapshots streamed from its artifacts file on `comm` (e.g. a rank group's), in the
/// distribution of `space` (a system's phase space on that communicator, kept alive by the caller).
/// InputError when the training holds its snapshots in memory.
SnapshotSet trainingSnapshotsOn(const TrainingResult& training, const RCP<const Comm>& comm, const PhaseSpace& space);

/// The shifted systems of the training parameters, each instantiated on `comm` when asked for
/// (SystemSet: two alive at a time). `scene` must outlive the set.
SystemSet trainingSystems(const Scene& scene, const RCP<const Comm>& comm, const TrainingResult& training);

}  // namespace gphr
