#pragma once
/// @file
/// The figures of one run that summary.json reports (an entry of its "runs"), typed: each metric is
/// an enumerator with one JSON key and one kind (text, integer, number, flag, numbers) in the table
/// of RunMetrics.cpp, the only place the keys are spelled. Stages set the metrics they measure,
/// reports read them back as values, and json() writes the entry in the order the stages set them
/// (the order summary.json has always had: evaluation first, then each method's own figures).
#include <utility>
#include <string>
#include <variant>
#include <vector>

#include "gphr/driver/Json.hpp"

namespace gphr {

/// One figure of a run's summary.json entry (doc/reference.md, "summary.json", lists every key).
enum class Metric : int {
  // identity and size
  Method, N, FullDim, NumTerms, K, ReducedDim, M, Steps, Dt, Ranks,
  // accuracy and the time loop (every evaluated run)
  EL2, EFin, EL2Estimate, H0, HErrMax, HErrFinal, HErrMaxRel, TOnlineS, TOnlineRunsS, NewtonItersAvg, NewtonMatrices, LinearItersAvg, LinearItersPerNewton, NewtonResidualMax,
  HDriftBound, ErrorsAt,
  // status
  UnboundedAtStep, UnboundedReason, Status, Reason, HModelErrMax, DivergedAtStep, DivergedReason,
  // the basis (rom)
  Basis, EnergyCaptured, TrainingParameters, TrainingReused, BasisCached,
  // term-weighted models: convexity and online size
  HessMinEigHr, HessMinEigRom, ConvexityLost, KernelRowsPerEvaluation, OnlineNumbersHeld,
  // the DEIM pair and basis
  CondPtU, DeimWeightMin, DeimWeightMax, DeimSnapshots, DeimBasisCached, DeimPodStepsTsqr, DeimPodStepsStacked, DeimPodStepsReplicated, DeimPodStepsTree,
  // empirical quadrature fits
  EqpTerms, EqpFitResidual, EqpFitResidualExactRows, EqpWeightMin, EqpWeightMax, EqpStop, EqpSelections, EqpCached,
  // GP-ADEIM
  Updates, UpdatesSkipped, UpdateRankMean, NumSamplesMean, InitialBasis, Sampling, Delta0, Delta, Window, Gamma,
  // offline and total times
  TTrainingS, TBasisS, TBasisCpuS, TDeimBasisS, TDeimBasisComputeS, TDeimPairS, TEqpTrainingS, TEqpFitS, TEqpMeshS, TInitialBasisS, TUpdatesS, TOfflineS, THyperOfflineS, TTotalS,
  // the POD routes of the basis
  PodRoute, PodStepsTsqr, PodStepsReplicated, PodStepsStacked, PodStepsTree,
};

/// The metrics one run has set (see the file's description).
class RunMetrics {
 public:
  /// Sets a metric; std::logic_error if its kind is another (a text metric given a number, ...).
  /// @{
  RunMetrics& set(Metric m, double value);
  RunMetrics& set(Metric m, long value);
  RunMetrics& set(Metric m, int value) { return set(m, static_cast<long>(value)); }
  RunMetrics& set(Metric m, bool value);
  RunMetrics& set(Metric m, const std::string& value);
  RunMetrics& set(Metric m, const char* value) { return set(m, std::string(value)); }
  RunMetrics& set(Metric m, const std::vector<double>& values);
  /// @}
  /// Sets every metric of `later`, in its order: one set here already is replaced in place.
  RunMetrics& merge(const RunMetrics& later);
  bool has(Metric m) const { return find(m) != nullptr; }  ///< Whether the run set it.
  /// A number or integer metric as a double; NaN when the run did not set it.
  double number(Metric m) const;
  /// A flag metric; false when the run did not set it.
  bool flag(Metric m) const;
  /// The entry of summary.json: every metric set, in the order first set.
  JsonObject json() const;
  /// The JSON key of a metric.
  static const char* key(Metric m);

 private:
  using Value = std::variant<double, long, bool, std::string, std::vector<double>>;
  RunMetrics& put(Metric m, Value v, int kind);
  const Value* find(Metric m) const;
  std::vector<std::pair<Metric, Value>> values_;  // in the order first set; a second set replaces
};

}  // namespace gphr
