#pragma once
/// @file
/// One evaluated reduced or hyper-reduced model of `gphr run` and `gphr validate`: the evaluation
/// library's record (ReducedEvaluation: histories, errors, times, status) with its method and
/// sizes, GP-ADEIM's update records and the figures its stage measured beyond the evaluation.
/// One record: summary.json's entry is written from these fields (json()), the stage's own
/// figures after the evaluation's.
#include <string>
#include <vector>

#include "gphr/core/Method.hpp"
#include "gphr/core/Types.hpp"
#include "gphr/driver/RunMetrics.hpp"
#include "gphr/evaluation/ReducedEvaluation.hpp"
#include "gphr/hyper/GpAdeimModel.hpp"

namespace gphr {

/// One evaluated reduced or hyper-reduced model (a "runs" entry of summary.json and its histories).
struct ModelRun : ReducedEvaluation {
  std::string method;  ///< rom | gp-deim | gp-adeim | deim | sdeim | gp-eqp | gp-eqp-refit
  /// Reduced size k (2k columns of A) and DEIM size m; m = 0 for rom.
  /// @{
  int k = 0, m = 0;
  /// @}
  long steps = 0;  ///< time steps of its evaluation
  std::vector<AdeimUpdateRecord> adeimUpdates;  ///< gp-adeim: one record per adaptation
  RunMetrics metrics;  ///< its stage's own figures (the DEIM pair's, the term weights', the offline times)
  std::string label() const;  ///< Method with k and m, as the report names the run.
  /// What its method is (the registry's entry: reports select runs by its traits).
  const MethodInfo& info() const { return methodInfo(method); }
  /// report.md: a run that failed or blew up in bold
  std::string statusText() const {
    const std::string name = statusName(status());
    return bounded() || !available ? name : "**" + name + "**";
  }
  /// Its "runs" entry of summary.json: the evaluation's figures, then the stage's.
  JsonObject json() const;
};

}  // namespace gphr
