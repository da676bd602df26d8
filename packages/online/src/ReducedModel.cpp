#include "gphr/online/ReducedModel.hpp"

#include <Teuchos_DefaultSerialComm.hpp>
#include <Teuchos_Time.hpp>

#include <chrono>
#include <cmath>
#include <unordered_map>

#include "gphr/core/BlasThreads.hpp"
#include "gphr/core/Error.hpp"
#include "gphr/core/ParameterValidation.hpp"
#include "gphr/core/YamlText.hpp"
#include "gphr/core/ReplicatedGather.hpp"
#include "gphr/hyper/GpAdeimModel.hpp"
#include "gphr/models/SceneFactory.hpp"
#include "gphr/core/Method.hpp"
#include "gphr/timeint/Integrator.hpp"

namespace gphr {

namespace {

// What the file stores as YAML, parsed within the limits of a user's file (YamlText.hpp).
// (Its top-level key is not held to one name: files written by a user's code may name it otherwise.)
Teuchos::RCP<Teuchos::ParameterList> storedSection(const std::string& text, const std::string& what) {
  return parseYamlText(text, "its " + what + " section");
}

std::shared_ptr<const Scene> sceneOf(const ReducedModelData& d) {
  GPHR_REQUIRE(!d.sceneConfig.empty(), InputError, "it is of scene '", d.sceneName,
               "', which is not built in: pass that scene to ReducedModel");
  const auto pl = storedSection(d.sceneConfig, "scene");
  try {
    return makeScene(*pl);
  } catch (const InputError& e) {
    throw InputError(detail::concat("its scene: ", e.what()));
  }
}

// y0(mu) at the given entries, picked from the basis' reference entries.
std::vector<double> pick(const StoredBasisData& b, const std::vector<double>& reference, const std::vector<GO>& gids) {
  std::unordered_map<GO, size_t> at;
  for (size_t i = 0; i < b.referenceGids.size(); ++i) at.emplace(b.referenceGids[i], i);
  std::vector<double> out;
  out.reserve(gids.size());
  for (GO g : gids) {
    const auto it = at.find(g);
    GPHR_REQUIRE(it != at.end(), InputError, "reduced-model file: state entry ", g, " has no reference value");
    out.push_back(reference[it->second]);
  }
  return out;
}

std::string boxText(const ReducedModelData& d) {
  std::string s;
  for (size_t p = 0; p < d.box.size(); ++p)
    s += detail::concat(p ? ", " : "", d.parameterNames[p], " in [", d.box[p].first, ", ", d.box[p].second, "]");
  return s;
}

}  // namespace

ReducedModel::ReducedModel(const std::string& path, std::shared_ptr<const Scene> scene)
    : file_(std::make_shared<const OpenModelFile>(path)), scene_(std::move(scene)) {
  checkLoaded();
}

ReducedModel::ReducedModel(ReducedModelData data, std::shared_ptr<const Scene> scene,
                           std::map<int, RCP<const MultiVector>> bases)
    : memory_(std::make_shared<const ReducedModelData>(std::move(data))), memoryBases_(std::move(bases)),
      scene_(std::move(scene)) {
  checkLoaded();
}

RCP<MultiVector> ReducedModel::basis(int k, const PhaseSpace& space) const {
  if (file_) return file_->basis(k, space);
  const auto it = memoryBases_.find(k);
  GPHR_REQUIRE(it != memoryBases_.end() && !it->second.is_null() && it->second->getMap()->isSameAs(*space.map()),
               InputError, path(), ": no basis of k = ", k, " on the given phase space");
  return rcp(new MultiVector(*it->second, Teuchos::Copy));
}

void ReducedModel::checkLoaded() {
  try {
    if (!scene_) scene_ = sceneOf(data());
    GPHR_REQUIRE(scene_->name() == data().sceneName, InputError, "it is of scene '", data().sceneName,
                 "', not of the scene '", scene_->name(), "' given");
    GPHR_REQUIRE(scene_->parameterBox().names == data().parameterNames, InputError,
                 "its parameters differ from scene '", scene_->name(), "''s");
    checkStoredSections();
  } catch (const InputError& e) {
    throw InputError(detail::concat("reduced-model file '", path(), "': ", e.what()));
  }
}

void ReducedModel::checkStoredSections() {
  const ReducedModelData& d = data();
  integrator_ = *storedSection(d.integratorConfig, "integrator");
  try {
    validateParameters(integrator_, integratorValidParameters(), "integrator");
  } catch (const InputError& e) {
    throw InputError(detail::concat("its integrator section: ", e.what()));
  }
  // The row kernel reads stencilSize() entries per row: a stored stencil of another width would
  // be found by the first query of that model (ReducedRowKernel), after its output was begun.
  std::vector<double> centre;
  for (const auto& [lo, hi] : d.box) centre.push_back(0.5 * (lo + hi));
  const int width = scene_->rowKernel(centre)->stencilSize();
  for (const auto& x : d.models) {
    if (methodInfo(x.method).needsFullResidual) {
      const auto pl = storedSection(x.adeimConfig, x.key() + " adeim");
      try {
        adeim_.emplace(x.key(), adeimOptionsFrom(*pl, x.m));
      } catch (const InputError& e) {
        throw InputError(detail::concat("its ", x.key(), " adeim section: ", e.what()));
      }
      continue;
    }
    const auto& st = x.sample.stencil;
    for (LO i = 0; width > 0 && i < st.numRows(); ++i)
      GPHR_REQUIRE(st.size(i) == width, InputError, "model ", x.key(), ": row ", x.sample.rows[i], " has ", st.size(i),
                   " stencil entries; allowed: ", width, " (the row kernel of scene ", d.sceneName, " reads ", width,
                   ")");
  }
}

OnlineParameterData ReducedModel::exactParameterData(const StoredBasisData& b, const std::vector<double>& mu) const {
  GPHR_REQUIRE(b.hasBasis, InputError, "setup 'exact' needs the basis in the reduced-model file (k = ", b.k,
               "); build it with build.withBasis: true, or use setup 'interpolated'");
  const auto inst = scene_->instantiate(rcp(new Teuchos::SerialComm<int>()), mu, true);
  const auto A = basis(b.k, inst.system->space());
  OnlineParameterData out;
  out.linear = reduceLinearPart(*inst.system, *A);
  out.reference = gatherRows(*inst.system->reference(), b.referenceGids);
  if (!b.indicator.empty()) out.indicator = indicatorLinearRows(*inst.system, *A, b.indicator.entries);
  return out;
}

bool ReducedModel::checkParameter(const std::vector<double>& mu, bool allowExtrapolation) const {
  GPHR_REQUIRE(mu.size() == data().box.size(), InputError, "a query of scene ", data().sceneName, " takes ",
               data().box.size(), " parameter(s) (", boxText(data()), "), got ", mu.size());
  bool outside = false;
  for (size_t p = 0; p < mu.size(); ++p) {
    GPHR_REQUIRE(std::isfinite(mu[p]), InputError, "parameter ", data().parameterNames[p], " = ", mu[p],
                 " is not a finite number");
    const bool inside = mu[p] >= data().box[p].first && mu[p] <= data().box[p].second;
    GPHR_REQUIRE(inside || allowExtrapolation, InputError, "parameter ", data().parameterNames[p], " = ", mu[p],
                 " is outside the training box (", boxText(data()),
                 "); allowed: inside it, or allowExtrapolation = true (a query's extrapolate: true)");
    outside = outside || !inside;
  }
  return outside;
}

std::shared_ptr<ResidualIndicator> ReducedModel::errorIndicator(const StoredBasisData& basis,
                                                                const OnlineParameterData& p,
                                                                RCP<const RowEvaluator> kernel) const {
  if (basis.indicator.empty()) return nullptr;
  std::vector<double> reference = pick(basis, p.reference, basis.indicator.entries);
  const auto terms = pick(basis, p.reference, basis.indicator.terms.stencil.gids);
  reference.insert(reference.end(), terms.begin(), terms.end());
  const Teuchos::ParameterList integ = validatedIntegrator(integrator_);
  return std::make_shared<ResidualIndicator>(
      kernel, basis.indicator, reference, p.indicator,
      quadratureFor(integ.get<std::string>("scheme"), integ.get<int>("quadraturePoints"), data().polynomialDegree));
}

OnlineModel ReducedModel::instantiate(const std::string& method, int k, int m, const std::vector<double>& mu,
                                      bool allowExtrapolation, SetupRoute route) const {
  const SingleBlasThread blas;  // the same bits whatever OPENBLAS_NUM_THREADS (core/BlasThreads.hpp)
  OnlineModel out;
  out.extrapolated_ = checkParameter(mu, allowExtrapolation);
  const StoredHyperModel& stored = data().model(method, k, m);
  GPHR_REQUIRE(!methodInfo(method).needsFullResidual, InputError, method, " k=", k, " m=", m,
               " samples the full residual online: use ReducedModel::simulateAdaptive (gphr query runs it on every "
               "rank)");
  const StoredBasisData& basis = data().basis(k);
  Teuchos::Time clock("setup");
  clock.start();
  const OnlineParameterData p = route == SetupRoute::Exact ? exactParameterData(basis, mu) : basis.at(mu);
  SampleMesh mesh;
  mesh.sample = stored.sample;
  mesh.sample.reference = pick(basis, p.reference, stored.sample.stencil.gids);
  mesh.linear = p.linear;
  const auto kernel = scene_->rowKernel(mu);
  out.model_ = rcp(new GpDeimModel(kernel, mesh));
  out.indicator_ = errorIndicator(basis, p, kernel);
  out.calibration_ = stored.calibration;
  out.integrator_ = integrator_;
  out.degree_ = data().polynomialDegree;
  out.mu_ = mu;
  out.probeGids_ = basis.probeGids;
  out.probeRows_ = basis.probeRows;
  out.probeReference_ = pick(basis, p.reference, basis.probeGids);
  out.setupSeconds_ = clock.stop();
  return out;
}

namespace {
// A run whose observer did not evaluate H_hr (none was given) has its last state's checked, so
// that a run whose energy is not a number is never `ok` (an observer checks every step).
SimulationStats unobservedEnergyChecked(SimulationStats stats, DenseHamiltonian& model, const DenseVector& z) {
  if (stats.ok() && !std::isfinite(model.hamiltonian(z))) {
    stats.status = RunStatus::Diverged;
    stats.reason = detail::concat("non-finite Hamiltonian at the last step ", stats.lastStep);
  }
  return stats;
}

// The error indicator along a query (hyper/ErrorIndicator.hpp) as the time loop's adaptive hook:
// its work counts in the query's online time, and is also reported on its own.
class IndicatorHook {
 public:
  IndicatorHook(ResidualIndicator* indicator, double dt) : indicator_(indicator), dt_(dt) {}
  void operator()(long j, const DenseVector& z) {
    if (!indicator_) return;
    const auto t0 = std::chrono::steady_clock::now();
    if (j == 0) indicator_->start(z);
    else indicator_->step(previous_, z, dt_);
    if (previous_.length() != z.length()) previous_.size(z.length());  // once: no allocation per step
    previous_.assign(z);
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  // The run's indicator and estimate (NaN unless it reached its end).
  SimulationStats report(SimulationStats stats, const IndicatorCalibration& calibration) const {
    stats.indicatorSeconds = seconds_;
    if (indicator_ && stats.ok()) {
      stats.errorIndicator = indicator_->value();
      stats.errorEstimate = calibration.estimate(stats.errorIndicator);
    }
    return stats;
  }

 private:
  ResidualIndicator* indicator_;
  double dt_, seconds_ = 0.0;
  DenseVector previous_;
};

// The time loop's settings of a query: the file's integrator at step dt over T / dt steps.
SimulationSettings settingsOf(const Teuchos::ParameterList& integrator, int degree, double T, double dt) {
  SimulationSettings out;
  out.dt = dt, out.steps = wholeSteps(T, dt), out.integrator = integrator, out.polynomialDegree = degree;
  return out;
}
}  // namespace

void OnlineModel::probeValues(const DenseVector& z, std::vector<double>& out) const {
  liftProbes(probeReference_, probeRows_, z, out);
}

SimulationStats OnlineModel::simulate(double T, double dt, const QueryObserver& observer) {
  const SingleBlasThread blas;  // the same bits whatever OPENBLAS_NUM_THREADS (core/BlasThreads.hpp)
  std::vector<double> probes;
  DenseVector z;
  const StepHook observe = [&](long j, double t, const DenseVector& zj) {
    const double H = finiteHamiltonian(model_->hamiltonian(zj), j);
    if (!probeGids_.empty()) probeValues(zj, probes);
    observer(QueryStep{j, t, zj, H, probes});
  };
  IndicatorHook indicate(indicator_.get(), dt);
  const StepHook adapt = [&](long j, double, const DenseVector& zj) { indicate(j, zj); };
  const SimulationSettings settings = settingsOf(integrator_, degree_, T, dt);
  if (observer) return indicate.report(gphr::simulate(*model_, settings, z, observe, adapt), calibration_);
  return indicate.report(unobservedEnergyChecked(gphr::simulate(*model_, settings, z, StepHook(), adapt), *model_, z),
                         calibration_);
}

RCP<GpAdeimModel> ReducedModel::adaptiveModel(int k, int m, const SceneInstance& inst, const RCP<const MultiVector>& A,
                                              double dt) const {
  const AdeimOptions& o = adeim_.at(data().model("gp-adeim", k, m).key());
  const auto U0 = initialAdeimBasis(inst.system, *inst.y0, *A, integrator_, dt, o.initialWindow, m);
  return rcp(new GpAdeimModel(inst.system, A, *U0, m, reduceLinearPart(*inst.system, *A), o));
}

SimulationStats ReducedModel::simulateAdaptive(int k, int m, const std::vector<double>& mu, double T, double dt,
                                               const RCP<const Comm>& comm, const QueryObserver& observer,
                                               double* setupSeconds, bool allowExtrapolation) const {
  const SingleBlasThread blas;  // the same bits whatever OPENBLAS_NUM_THREADS (core/BlasThreads.hpp)
  checkParameter(mu, allowExtrapolation);
  const StoredBasisData& basis = data().basis(k);
  GPHR_REQUIRE(basis.hasBasis, InputError, "gp-adeim k=", k, " needs the basis in the file (build.withBasis: true)");
  Teuchos::Time clock("adaptive setup");
  clock.start();
  const auto inst = scene_->instantiate(comm, mu, true);
  const RCP<const MultiVector> A = this->basis(k, inst.system->space());
  const RCP<GpAdeimModel> hr = adaptiveModel(k, m, inst, A, dt);
  GpAdeimModel& model = *hr;
  const auto y0 = gatherRows(*inst.system->reference(), basis.probeGids);
  if (setupSeconds) *setupSeconds = clock.stop();
  std::vector<double> probes;
  const StepHook observe = [&](long j, double t, const DenseVector& z) {
    const double H = finiteHamiltonian(model.hamiltonian(z), j);  // H_hr^j of the model of this step
    liftProbes(y0, basis.probeRows, z, probes);
    observer(QueryStep{j, t, z, H, probes});
  };
  DenseVector z;
  const SimulationSettings settings = settingsOf(integrator_, data().polynomialDegree, T, dt);
  // the indicator on the file's interpolated data, as every other query's
  const auto indicator = errorIndicator(basis, basis.at(mu), scene_->rowKernel(mu));
  IndicatorHook indicate(indicator.get(), dt);
  const StepHook update = adeimUpdateHook(model);
  const StepHook adapt = [&](long j, double t, const DenseVector& zj) {
    indicate(j, zj);
    update(j, t, zj);
  };
  const IndicatorCalibration& calibration = data().model(method::kGpAdeim, k, m).calibration;
  if (observer) return indicate.report(gphr::simulate(model, settings, z, observe, adapt), calibration);
  return indicate.report(unobservedEnergyChecked(gphr::simulate(model, settings, z, StepHook(), adapt), model, z),
                         calibration);
}

}  // namespace gphr
