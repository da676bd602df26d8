#pragma once
/// @file
/// The full-order-model stage of `gphr run` and `gphr validate`: the evaluation library's
/// reference (FullModelReference) with what summary.json reports of it and, where the run shows
/// fields, the collector of the reduced runs' field states.
#include <memory>
#include <string>
#include <vector>

#include "gphr/driver/Json.hpp"
#include "gphr/evaluation/FullModelReference.hpp"

namespace gphr {

class FieldStates;

/// The full model's results at the test parameter (the reference) and its sizes.
struct FomResult : FullModelReference {
  int ranks = 1;    ///< MPI ranks of its run
  double dt = 0.0;  ///< its time step
  long steps = 0;   ///< its steps
  /// The reduced runs' lifted states the field outputs show, collected as the runs are evaluated
  /// against this full model (FieldModels.hpp); null when no field output is asked for.
  std::shared_ptr<FieldStates> fieldStates;
  JsonObject json() const;  ///< its "runs" entry of summary.json
};


/// A reference of the library as the run's result; fieldModels: the names whose field states it
/// collects (none: no collector).
FomResult fomResultOf(FullModelReference reference, const EvaluationSettings& settings, int ranks,
                      const std::vector<std::string>& fieldModels = {});

/// Integrates the scene's full model at parameter `mu` (runFullModel) into a FomResult.
FomResult runFom(const EvaluationSettings& settings, const Scene& scene, const std::vector<double>& mu,
                 const RCP<const Comm>& comm, const std::vector<std::string>& fieldModels = {});

}  // namespace gphr
