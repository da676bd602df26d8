// The calibration of the online error indicator on the training parameters (ErrorCalibration.hpp).
#include "gphr/offline/ErrorCalibration.hpp"

#include <cmath>
#include <limits>

#include "gphr/core/Error.hpp"
#include "gphr/core/Method.hpp"
#include "gphr/online/Lift.hpp"
#include "gphr/online/ReducedModel.hpp"

namespace gphr {

namespace {

// E_L2 (eq:errNR) of the lift A z at the snapshot columns of training block j: the snapshots are
// shifted states X, the physical ones X + y0. z: the reduced states at those columns, 2k each.
double trajectoryError(const MultiVector& A, const SnapshotSet& snapshots, size_t j, const std::vector<double>& z,
                       const Vector& y0) {
  const int r = static_cast<int>(A.getNumVectors());
  const size_t columns = z.size() / r;
  double num = 0.0, den = 0.0;
  const size_t block = kSnapshotReadColumns;
  const auto Z = liftWorkspace(A, static_cast<int>(block));
  MultiVector Y(A.getMap(), block);
  Vector x(A.getMap());
  for (size_t c0 = 0; c0 < columns; c0 += block) {
    const size_t count = std::min(block, columns - c0);
    const auto X = snapshots.columns(j, 1, c0, count);
    liftStates(A, nullptr, &z[c0 * r], static_cast<int>(count), *Z, Y);
    for (size_t c = 0; c < count; ++c) {
      const auto xc = X->getVector(c);
      const auto yc = Y.getVectorNonConst(c);
      yc->update(1.0, *xc, -1.0);  // X - A z
      x.update(1.0, *xc, 1.0, y0, 0.0);  // the physical state
      const double e = yc->norm2(), nx = x.norm2();
      num += e * e, den += nx * nx;
    }
  }
  return den > 0.0 ? std::sqrt(num / den) : std::numeric_limits<double>::quiet_NaN();
}

// The model's run at mu as a query runs it: its indicator and its states at the snapshot steps.
SimulationStats runAsQuery(const ReducedModel& rm, const StoredHyperModel& x, const std::vector<double>& mu,
                           const HamiltonianSystem& like, double dt, long steps, long every, size_t columns,
                           std::vector<double>& z) {
  z.clear();
  const QueryObserver keep = [&](const QueryStep& s) {
    if (s.step % every == 0 && static_cast<size_t>(s.step / every) < columns)
      z.insert(z.end(), s.z.values(), s.z.values() + s.z.length());
  };
  const double T = dt * static_cast<double>(steps);
  if (x.onlineNeedsFullSystem())
    return rm.simulateAdaptive(x.k, x.m, mu, T, dt, like.space().comm(), keep, nullptr);
  return rm.instantiate(x.method, x.k, x.m, mu).simulate(T, dt, keep);
}

}  // namespace

std::map<std::string, std::vector<CalibrationPoint>> measureModelErrors(
    const ReducedModelData& data, const Scene& scene, const HamiltonianSystem& like,
    const std::map<int, RCP<const MultiVector>>& bases, const TrainingResult& training, long snapshotEvery,
    double dt, long steps) {
  std::map<std::string, std::vector<CalibrationPoint>> points;
  const std::shared_ptr<const Scene> sceneRef(&scene, [](const Scene*) {});  // not owned: the caller's
  ReducedModelData held = data;  // the bases are in memory, not (yet) in a file: gp-adeim reads them there
  for (auto& b : held.bases) b.hasBasis = bases.count(b.k) && !bases.at(b.k).is_null();
  const ReducedModel rm(std::move(held), sceneRef, bases);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (size_t j = 0; j < training.parameters.size(); ++j) {
    const auto& mu = training.parameters[j];
    const auto inst = scene.instantiate(like, mu, true);
    for (const auto& x : data.models) {
      const auto A = bases.find(x.k);
      if (data.basis(x.k).indicator.empty() || A == bases.end() || A->second.is_null()) continue;
      std::vector<double> z;
      const SimulationStats stats = runAsQuery(rm, x, mu, like, dt, steps, snapshotEvery,
                                               training.snapshots.numColumns(j), z);
      CalibrationPoint p{mu, stats.errorIndicator, nan};
      if (stats.ok() && z.size() == training.snapshots.numColumns(j) * A->second->getNumVectors())
        p.error = trajectoryError(*A->second, training.snapshots, j, z, *inst.system->reference());
      points[x.key()].push_back(p);
    }
  }
  return points;
}

std::map<std::string, std::vector<CalibrationPoint>> calibrateErrorIndicators(
    ReducedModelData& data, const Scene& scene, const HamiltonianSystem& like,
    const std::map<int, RCP<const MultiVector>>& bases, const TrainingResult& training, long snapshotEvery,
    double dt, long steps) {
  auto points = measureModelErrors(data, scene, like, bases, training, snapshotEvery, dt, steps);
  for (auto& x : data.models) {
    std::vector<double> eta, err;
    for (const auto& p : points[x.key()]) eta.push_back(p.indicator), err.push_back(p.error);
    x.calibration = fitIndicatorCalibration(eta, err);
  }
  return points;
}

}  // namespace gphr
