#include "gphr/online/ReducedModel.hpp"

#include <Teuchos_DefaultSerialComm.hpp>
#include <Teuchos_Time.hpp>
#include <Teuchos_YamlParameterListCoreHelpers.hpp>

#include <cmath>
#include <unordered_map>

#include "gphr/core/Error.hpp"
#include "gphr/core/ReplicatedGather.hpp"
#include "gphr/hyper/GpAdeimModel.hpp"
#include "gphr/models/SceneFactory.hpp"
#include "gphr/online/Method.hpp"

namespace gphr {

namespace {

std::shared_ptr<const Scene> sceneOf(const ReducedModelData& d, const std::string& path) {
  GPHR_REQUIRE(!d.sceneConfig.empty(), InputError, "reduced-model file '", path, "' is of scene '", d.sceneName,
               "', which is not built in: pass that scene to ReducedModel");
  auto pl = Teuchos::getParametersFromYamlString(d.sceneConfig);
  try {
    return makeScene(*pl);
  } catch (const InputError& e) {
    throw InputError(detail::concat("reduced-model file '", path, "': its scene: ", e.what()));
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
    : path_(path), data_(readReducedModelFile(path)), scene_(scene ? scene : sceneOf(data_, path)) {
  GPHR_REQUIRE(scene_->name() == data_.sceneName, InputError, "reduced-model file '", path, "' is of scene '",
               data_.sceneName, "', not of the scene '", scene_->name(), "' given");
  GPHR_REQUIRE(scene_->parameterBox().names == data_.parameterNames, InputError, "reduced-model file '", path,
               "': its parameters differ from scene '", scene_->name(), "''s");
}

OnlineParameterData ReducedModel::exactParameterData(const StoredBasisData& b, const std::vector<double>& mu) const {
  GPHR_REQUIRE(b.hasBasis, InputError, "setup 'exact' needs the basis in the reduced-model file (k = ", b.k,
               "); build it with build.withBasis: true, or use setup 'interpolated'");
  const auto inst = scene_->instantiate(rcp(new Teuchos::SerialComm<int>()), mu, true);
  const auto A = readReducedModelBasis(path_, b.k, inst.system->space());
  OnlineParameterData out;
  out.linear = reduceLinearPart(*inst.system, *A);
  out.reference = gatherRows(*inst.system->reference(), b.referenceGids);
  return out;
}

bool ReducedModel::checkParameter(const std::vector<double>& mu, bool allowExtrapolation) const {
  GPHR_REQUIRE(mu.size() == data_.box.size(), InputError, "a query of scene ", data_.sceneName, " takes ",
               data_.box.size(), " parameter(s) (", boxText(data_), "), got ", mu.size());
  bool outside = false;
  for (size_t p = 0; p < mu.size(); ++p) {
    GPHR_REQUIRE(std::isfinite(mu[p]), InputError, "parameter ", data_.parameterNames[p], " = ", mu[p],
                 " is not a finite number");
    const bool inside = mu[p] >= data_.box[p].first && mu[p] <= data_.box[p].second;
    GPHR_REQUIRE(inside || allowExtrapolation, InputError, "parameter ", data_.parameterNames[p], " = ", mu[p],
                 " is outside the training box (", boxText(data_), "); allowed: inside it, or extrapolate: true");
    outside = outside || !inside;
  }
  return outside;
}

OnlineModel ReducedModel::instantiate(const std::string& method, int k, int m, const std::vector<double>& mu,
                                      bool allowExtrapolation, SetupRoute route) const {
  OnlineModel out;
  out.extrapolated_ = checkParameter(mu, allowExtrapolation);
  const StoredHyperModel& stored = data_.model(method, k, m);
  GPHR_REQUIRE(!methodInfo(method).needsFullResidual, InputError, method, " k=", k, " m=", m,
               " samples the full residual online: use ReducedModel::simulateAdaptive (gphr query runs it on every "
               "rank)");
  const StoredBasisData& basis = data_.basis(k);
  Teuchos::Time clock("setup");
  clock.start();
  const OnlineParameterData p = route == SetupRoute::Exact ? exactParameterData(basis, mu) : basis.at(mu);
  SampleMesh mesh;
  mesh.sample = stored.sample;
  mesh.sample.reference = pick(basis, p.reference, stored.sample.stencil.gids);
  mesh.linear = p.linear;
  out.model_ = rcp(new GpDeimModel(scene_->rowKernel(mu), mesh));
  out.integrator_ = *Teuchos::getParametersFromYamlString(data_.integratorConfig);
  out.degree_ = data_.polynomialDegree;
  out.mu_ = mu;
  out.probeGids_ = basis.probeGids;
  out.probeRows_ = basis.probeRows;
  out.probeReference_ = pick(basis, p.reference, basis.probeGids);
  out.setupSeconds_ = clock.stop();
  return out;
}

namespace {
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
  std::vector<double> probes;
  DenseVector z;
  const StepHook observe = [&](long j, double t, const DenseVector& zj) {
    const double H = model_->hamiltonian(zj);
    if (!probeGids_.empty()) probeValues(zj, probes);
    observer(QueryStep{j, t, zj, H, probes});
  };
  return gphr::simulate(*model_, settingsOf(integrator_, degree_, T, dt), z, observer ? observe : StepHook());
}

RCP<GpAdeimModel> ReducedModel::adaptiveModel(int k, int m, const SceneInstance& inst, const RCP<const MultiVector>& A,
                                              double dt) const {
  const StoredHyperModel& stored = data_.model("gp-adeim", k, m);
  const auto integrator = *Teuchos::getParametersFromYamlString(data_.integratorConfig);
  const AdeimOptions o = adeimOptionsFrom(*Teuchos::getParametersFromYamlString(stored.adeimConfig), m);
  const auto U0 = initialAdeimBasis(inst.system, *inst.y0, *A, integrator, dt, o.initialWindow, m);
  return rcp(new GpAdeimModel(inst.system, A, *U0, m, reduceLinearPart(*inst.system, *A), o));
}

SimulationStats ReducedModel::simulateAdaptive(int k, int m, const std::vector<double>& mu, double T, double dt,
                                               const RCP<const Comm>& comm, const QueryObserver& observer,
                                               double* setupSeconds, bool allowExtrapolation) const {
  checkParameter(mu, allowExtrapolation);
  const StoredBasisData& basis = data_.basis(k);
  GPHR_REQUIRE(basis.hasBasis, InputError, "gp-adeim k=", k, " needs the basis in the file (build.withBasis: true)");
  Teuchos::Time clock("adaptive setup");
  clock.start();
  const auto inst = scene_->instantiate(comm, mu, true);
  const RCP<const MultiVector> A = readReducedModelBasis(path_, k, inst.system->space());
  const auto integrator = *Teuchos::getParametersFromYamlString(data_.integratorConfig);
  const RCP<GpAdeimModel> hr = adaptiveModel(k, m, inst, A, dt);
  GpAdeimModel& model = *hr;
  const auto y0 = gatherRows(*inst.system->reference(), basis.probeGids);
  if (setupSeconds) *setupSeconds = clock.stop();
  std::vector<double> probes;
  const StepHook observe = [&](long j, double t, const DenseVector& z) {
    if (!observer) return;
    liftProbes(y0, basis.probeRows, z, probes);
    observer(QueryStep{j, t, z, model.hamiltonian(z), probes});  // H_hr^j of the model of this step
  };
  DenseVector z;
  return gphr::simulate(model, settingsOf(integrator, data_.polynomialDegree, T, dt), z, observe,
                        adeimUpdateHook(model));
}

}  // namespace gphr
