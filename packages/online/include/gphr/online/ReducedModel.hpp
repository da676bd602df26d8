#pragma once
/// @file
/// A reduced-model file loaded for simulation: the class an embedding code uses (and `gphr query`).
///
///   gphr::ReducedModel rm("nls.h5");                        // reads the file on this process
///   auto online = rm.instantiate("gp-deim", 10, 20, {1.05}); // the model at eps = 1.05
///   online.simulate(5.0, 0.01, [](const gphr::QueryStep& s) { ... s.z, s.hamiltonian, s.probes ... });
///
/// The file is held open, read-only, for the object's lifetime (OpenModelFile): everything it is
/// used for -- the model data, checked whole when loaded, and a basis read later -- comes from that
/// one file, even if another is written over its path meanwhile. The loading also checks what
/// the file stores for its scene: the scene, integrator and adeim sections (bounded YAML, through
/// the same validators as a config file) and every sample mesh's stencil widths against the
/// scene's row kernel, so that a bad file fails here, naming itself, not in a query.
///
/// MPI and Kokkos must run around every use (Tpetra::ScopeGuard in main, or the caller's own
/// initialisation): doc/embedding.md is a whole program, compiled and run by the tests, with the
/// CMake project, queries spread over ranks, observers, lifting and errors.
///
/// Loading and instantiate() are not collective and, on the default (interpolated) set-up route,
/// nothing of size n or d is allocated: the scene object only supplies its row kernel at mu, the file the sample
/// mesh and the parameter interpolant. The exact route builds the full system at mu and projects
/// it (O(n k), reported as setup time); it needs the basis in the file.
///
/// instantiate(), OnlineModel::simulate() and simulateAdaptive() run OpenBLAS on one thread while
/// they work (SingleBlasThread, core/BlasThreads.hpp; the caller's count is restored after, and the
/// observer runs under it too), so a query's bits do not depend on OPENBLAS_NUM_THREADS, as
/// `gphr query`'s do not. A code that runs queries on threads of its own pins OpenBLAS once
/// (a SingleBlasThread) before starting them, as `gphr query` does.
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gphr/hyper/GpAdeimModel.hpp"
#include "gphr/hyper/GpDeimModel.hpp"
#include "gphr/hyper/ReducedModelFile.hpp"
#include "gphr/models/Scene.hpp"
#include "gphr/online/Lift.hpp"
#include "gphr/online/TimeLoop.hpp"

namespace gphr {

/// How a query obtains what its parameter changes in L_r, f_r, c and the reference rows.
enum class SetupRoute { Interpolated, Exact };

/// What the observer sees after each step (and at step 0): probes are the lifted physical state
/// y0 + A z at the file's probe entries (empty when the model was built without probes).
struct QueryStep {
  long step;  ///< Time step index j.
  double time;  ///< Time t_j.
  const DenseVector& z;  ///< The reduced state z^j.
  double hamiltonian;                  ///< H_hr(z)
  const std::vector<double>& probes;  ///< Lifted state at the probe entries.
};
using QueryObserver = std::function<void(const QueryStep&)>;  ///< Called by OnlineModel::simulate() after each step.

/// One hyper-reduced model at one parameter.
class OnlineModel {
 public:
  int reducedDim() const { return model_->dim(); }  ///< 2k, the reduced size.
  /// Seconds to set the model up at its parameter (interpolated or exact route).
  double setupSeconds() const { return setupSeconds_; }
  bool extrapolated() const { return extrapolated_; }  ///< Whether the parameter lies outside the file's box.
  const std::vector<double>& parameter() const { return mu_; }  ///< The parameter mu.
  const std::vector<GO>& probeGids() const { return probeGids_; }  ///< Global ids of the probe entries of y.
  GpDeimModel& model() { return *model_; }  ///< The GP-DEIM model (sample mesh and row kernel at mu).
  /// From z = 0 (the shifted initial state y0(mu)) over T / dt steps (T a whole number of steps).
  /// A Newton failure or a non-finite state ends the run with status `diverged`, not an exception.
  /// The stats carry the run's error indicator and, where the file calibrated it, its error
  /// estimate (SimulationStats::errorEstimate; doc/error-estimate.md).
  SimulationStats simulate(double T, double dt, const QueryObserver& observer = {});
  /// Whether the model has an error indicator (the file holds indicator rows of its k).
  bool hasErrorIndicator() const { return static_cast<bool>(indicator_); }
  const IndicatorCalibration& calibration() const { return calibration_; }  ///< The file's calibration of the model.
  /// The lifted physical state at the probe entries.
  void probeValues(const DenseVector& z, std::vector<double>& out) const;

 private:
  friend class ReducedModel;
  RCP<GpDeimModel> model_;
  Teuchos::ParameterList integrator_;  ///< the file's integrator section
  int degree_ = 0;                     ///< polynomial degree of the scene's G
  std::vector<double> mu_;
  std::vector<GO> probeGids_;
  std::vector<double> probeRows_, probeReference_;
  double setupSeconds_ = 0.0;
  bool extrapolated_ = false;
  std::shared_ptr<ResidualIndicator> indicator_;  ///< null: the file has no indicator rows of this k
  IndicatorCalibration calibration_;
};

/// A reduced-model file loaded for simulation (see the file's description).
class ReducedModel {
 public:
  /// scene: the scene the file was built for; null makes it from the file's scene section (the
  /// built-in scenes). A user's own scene is passed here; its name must match the file's.
  /// InputError naming the file for any check it fails (see the file's description).
  explicit ReducedModel(const std::string& path, std::shared_ptr<const Scene> scene = nullptr);
  /// The model data in memory, not (yet) in a file (the build calibrates its error indicators
  /// on it): the same checks of the scene and the stored sections. basis(k, space) gives bases[k]
  /// where its map is space's (InputError otherwise, and for a k it does not hold).
  ReducedModel(ReducedModelData data, std::shared_ptr<const Scene> scene,
               std::map<int, RCP<const MultiVector>> bases);
  const std::string& path() const { return file_ ? file_->path() : inMemory_; }  ///< Path of the file.
  const ReducedModelData& data() const { return file_ ? file_->data() : *memory_; }  ///< The file's contents.
  const Scene& scene() const { return *scene_; }  ///< The scene the file was built for.
  /// The file's integrator section, validated (the time scheme and Newton of every query).
  const Teuchos::ParameterList& integrator() const { return integrator_; }
  /// The basis A of k on space's map, from the open file (OpenModelFile::basis: collective over
  /// space's communicator; InputError if the file holds none or it fails its checks).
  RCP<MultiVector> basis(int k, const PhaseSpace& space) const;
  /// InputError naming the box unless mu is inside it or allowExtrapolation is set (then the
  /// result is marked extrapolated); InputError naming the models held if (method, k, m) is not.
  OnlineModel instantiate(const std::string& method, int k, int m, const std::vector<double>& mu,
                          bool allowExtrapolation = false, SetupRoute route = SetupRoute::Interpolated) const;
  /// The GP-ADEIM model of (k, m) on a shifted instance of the scene and the file's basis A of k:
  /// its options from the file, (U_0, P_0) from the first delta0 full-model steps with step dt.
  /// Collective over the instance's communicator.
  RCP<GpAdeimModel> adaptiveModel(int k, int m, const SceneInstance& instance, const RCP<const MultiVector>& A,
                                  double dt) const;
  /// GP-ADEIM at mu (alg:SP-ADEIM): it samples the full residual online, so this builds the full
  /// system on `comm` from the scene and the file's basis, takes (U_0, P_0) from the first delta0
  /// full-model steps and adapts as it runs. Collective; the observer sees the same on every rank.
  /// setupSeconds receives the set-up time (system, basis, initial DEIM pair).
  SimulationStats simulateAdaptive(int k, int m, const std::vector<double>& mu, double T, double dt,
                                   const RCP<const Comm>& comm, const QueryObserver& observer, double* setupSeconds,
                                   bool allowExtrapolation = false) const;

 private:
  void checkStoredSections();  ///< the load-time checks of the scene, integrator and adeim sections
  /// The error indicator of k at mu from the parameter data p (null where the file has none).
  std::shared_ptr<ResidualIndicator> errorIndicator(const StoredBasisData& basis, const OnlineParameterData& p,
                                                    RCP<const RowEvaluator> kernel) const;
  OnlineParameterData exactParameterData(const StoredBasisData& basis, const std::vector<double>& mu) const;
  bool checkParameter(const std::vector<double>& mu, bool allowExtrapolation) const;  ///< true if outside the box
  void checkLoaded();  ///< the checks of both constructors, InputError naming path()
  std::shared_ptr<const OpenModelFile> file_;  ///< null: the data are in memory
  std::shared_ptr<const ReducedModelData> memory_;
  std::map<int, RCP<const MultiVector>> memoryBases_;
  std::string inMemory_ = "(model data in memory)";
  std::shared_ptr<const Scene> scene_;
  Teuchos::ParameterList integrator_;
  std::map<std::string, AdeimOptions> adeim_;  ///< per gp-adeim model's key, its options
};

}  // namespace gphr
