#pragma once
/// @file
/// One evaluated reduced or hyper-reduced model of `gphr run` and `gphr validate`: its method and
/// sizes, its histories, its status (RunStatus.hpp) and its metrics (RunMetrics.hpp).
#include <string>
#include <vector>

#include "gphr/core/Method.hpp"
#include "gphr/core/Types.hpp"
#include "gphr/driver/RunMetrics.hpp"
#include "gphr/hyper/GpAdeimModel.hpp"
#include "gphr/online/RunStatus.hpp"

namespace gphr {

/// One evaluated reduced or hyper-reduced model (a "runs" entry of summary.json and its histories).
struct ModelRun {
  std::string method;  ///< rom | gp-deim | gp-adeim | deim | sdeim
  /// Reduced size k (2k columns of A) and DEIM size m; m = 0 for rom.
  /// @{
  int k = 0, m = 0;
  /// @}
  std::vector<double> hamiltonian;       ///< H(y0 + A z^j) per step: the true Hamiltonian of the lift
  std::vector<double> modelHamiltonian;  ///< the model's own H_r / H_hr per step (empty without one)
  std::vector<double> errors;            ///< ||y^j - (y0 + A z^j)|| at the saved steps
  std::vector<double> stateNorms;        ///< ||y0 + A z^j|| per step
  std::vector<RCP<Vector>> states;       ///< lifted physical states at the saved steps, until FieldStates takes them
  std::vector<AdeimUpdateRecord> adeimUpdates;  ///< gp-adeim: one record per adaptation
  /// The error E_L2 (paper eq:errNR) and the online wall seconds.
  /// @{
  double eL2 = 0.0, tOnline = 0.0;
  /// @}
  bool ok = true;  ///< False: Newton failed or the state became non-finite (status diverged), or not run (unavailable).
  bool available = true;  ///< false: not run, the offline data cannot support this (k, m)
  long unboundedAt = -1;  ///< >= 0: ran to the end, but its lift left the full model's range at this step
  std::string unboundedReason;  ///< which bound it passed, with the figures
  RunMetrics metrics;  ///< The figures of its "runs" entry of summary.json.
  std::string label() const;  ///< Method with k and m, as the report names the run.
  /// What its method is (the registry's entry: reports select runs by its traits).
  const MethodInfo& info() const { return methodInfo(method); }
  /// ok | unbounded | diverged | unavailable (RunStatus.hpp)
  RunStatus status() const { return runStatus(ok, available, unboundedAt); }
  bool bounded() const { return ok && unboundedAt < 0; }  ///< status ok
  /// report.md: a run that failed or blew up in bold
  std::string statusText() const {
    const std::string name = statusName(status());
    return bounded() || !available ? name : "**" + name + "**";
  }
};

}  // namespace gphr
