#pragma once
/// @file
/// The reduced-model stages of `gphr run` (issue: offline training and Galerkin ROM):
///   train  - full model over the training set; shifted snapshots of each parameter go to
///            DIR/artifacts.h5 `/training/p<j>` as soon as it finishes (resumable, see Training);
///   reduce - symplectic basis from all snapshots, cached in /basis with its provenance;
///   rom    - the Galerkin ROM at the test parameter, errors eq:errNR against the full model.
#include <map>
#include <string>
#include <vector>

#include "gphr/driver/FomStage.hpp"
#include "gphr/driver/ModelRun.hpp"
#include "gphr/driver/RunContext.hpp"
#include "gphr/hyper/DeimBasis.hpp"
#include "gphr/hyper/EmpiricalQuadrature.hpp"
#include "gphr/hyper/GpAdeimModel.hpp"
#include "gphr/reduction/SymplecticBasis.hpp"

namespace gphr {

/// The training stage's results: the training parameters and their shifted snapshots.
struct TrainingResult {
  std::vector<std::vector<double>> parameters;  ///< The training parameters mu.
  std::vector<RCP<const MultiVector>> snapshots;  ///< shifted states per training parameter
  long reused = 0;                                 ///< parameters taken from the file
  double seconds = 0.0;  ///< Wall seconds of the stage.
};

/// The offline stages of `gphr run` and the reduced models they produced.
struct RomStages {
  TrainingResult training;  ///< The training stage.
  ReducedBasis basis;  ///< The symplectic basis A.
  bool basisCached = false;  ///< Whether the basis was read from artifacts.h5.
  double basisSeconds = 0.0;  ///< Wall seconds of the basis stage.
  double basisCpuSeconds = 0.0;           ///< rank 0's process CPU time in the basis stage
  std::vector<ModelRun> runs;             ///< rom, then the hyper-reduced models
  std::vector<double> deimSingularValues; ///< of the reduced-Jacobian snapshots (largest k)
};

/// Resumable training: a parameter whose dataset is complete in the file is reused, one without
/// its `complete` mark (killed mid-write) is redone. A file of another scene or size is an
/// InputError naming the file; a changed training config starts the training over.
TrainingResult runTraining(const RunContext& ctx);
/// The reduction stage: the symplectic basis from all training snapshots, read from the cache when its key matches.
ReducedBasis runReduction(const RunContext& ctx, const TrainingResult& training, bool& cached);
/// The k the basis is built for: the largest of reduction.k and pipeline.k.
int basisK(const Teuchos::ParameterList& cfg);
/// Provenance keys of the cached artifacts (the config text each one depends on).
std::string trainingKey(const Teuchos::ParameterList& cfg);
/// The provenance key of the cached basis.
std::string basisKey(const Teuchos::ParameterList& cfg);
/// The reduced-Jacobian DEIM basis of size k (hyper section of the config), from the cache in
/// artifacts.h5 `/deim/k<k>` when its key matches, else computed from the training snapshots and
/// cached. `test` supplies the row map of G. Collective.
struct CachedDeimBasis {
  DeimBasis basis;  ///< The reduced-Jacobian DEIM basis.
  bool cached = false;  ///< Whether it was read from the cache.
  double seconds = 0.0;         ///< this run: computing it, or reading the cache
  double computeSeconds = 0.0;  ///< computing it (stored with the cache): the offline cost it stands for
};
/// The reduced-Jacobian DEIM basis of size k (see CachedDeimBasis), from the cache or computed.
CachedDeimBasis deimBasisFor(const RunContext& ctx, const RomStages& st, const MultiVector& A, int k,
                             const HamiltonianSystem& test);
/// The terms and weights of gp-eqp (non-negative, NNLS) or gp-eqp-refit (GP-DEIM's terms, least
/// squares) for reduced size k and each budget of ms, from the artifacts.h5 cache when its key
/// matches, else fitted (section eqp, one training system for all budgets) and cached. A budget the
/// training cannot support is left out, its reason in `skipped`.
std::map<int, QuadratureFit> termWeightFits(const RunContext& ctx, RomStages& st, const MultiVector& A, int k,
                                            const HamiltonianSystem& test, const std::string& method,
                                            const std::vector<int>& ms, std::map<int, std::string>& skipped);
/// The hyper-reduced models of pipeline.methods (gp-deim, deim, sdeim) for every k and m.
void runHyperReduction(const RunContext& ctx, const FomResult& fom, RomStages& stages);
/// The training and basis keys of a rom / gp-deim entry: t_training_s, t_basis_s, t_basis_cpu_s,
/// pod_route and the basis's POD steps by route.
void setBasisKeys(const RunContext& ctx, const RomStages& stages, JsonObject& run);
/// Galerkin ROM at the test parameter for every k; errors against the full model's saved states.
void runRom(const RunContext& ctx, const FomResult& fom, RomStages& stages);

}  // namespace gphr
