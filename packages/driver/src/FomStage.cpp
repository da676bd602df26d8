#include "gphr/driver/FomStage.hpp"

#include <cmath>

#include "gphr/core/Method.hpp"
#include "gphr/driver/FieldModels.hpp"
#include "gphr/driver/RunMetrics.hpp"

namespace gphr {

FomResult fomResultOf(FullModelReference reference, const EvaluationSettings& settings, int ranks,
                      const std::vector<std::string>& fieldModels) {
  FomResult res;
  static_cast<FullModelReference&>(res) = std::move(reference);
  res.ranks = ranks, res.dt = settings.time.dt, res.steps = settings.time.steps;
  if (!fieldModels.empty()) res.fieldStates = std::make_shared<FieldStates>(fieldModels, res.trajectory->getNumVectors());
  return res;
}

FomResult runFom(const EvaluationSettings& settings, const Scene& scene, const std::vector<double>& mu,
                 const RCP<const Comm>& comm, const std::vector<std::string>& fieldModels) {
  return fomResultOf(runFullModel(settings, scene, mu, comm), settings, comm->getSize(), fieldModels);
}

JsonObject FomResult::json() const {
  const double H0 = hamiltonian.front(), herr = maxDeviation(hamiltonian, H0);
  RunMetrics m;
  m.set(Metric::Method, method::kFom)
      .set(Metric::N, n)
      .set(Metric::FullDim, fullDim)
      .set(Metric::NumTerms, numTerms)
      .set(Metric::Steps, steps)
      .set(Metric::Dt, dt)
      .set(Metric::Ranks, ranks)
      .set(Metric::TOnlineS, tOnline)
      .set(Metric::NewtonItersAvg, double(stats.newtonIterations) / steps)
      .set(Metric::LinearItersAvg, double(stats.linearIterations) / steps)
      .set(Metric::LinearItersPerNewton, stats.newtonIterations ? double(stats.linearIterations) / stats.newtonIterations : 0.0)
      .set(Metric::NewtonResidualMax, stats.maxResidual)
      .set(Metric::HDriftBound, driftBound)
      .set(Metric::H0, H0)
      .set(Metric::HErrMax, herr)
      .set(Metric::HErrMaxRel, H0 != 0.0 ? herr / std::abs(H0) : herr)
      .set(Metric::Status, "ok");
  return m.json();
}

}  // namespace gphr
