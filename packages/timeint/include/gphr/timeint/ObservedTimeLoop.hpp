#pragma once
/// @file
/// The one observed time loop: the full model's runs (`gphr run`'s reference, validate's, the
/// training's snapshots, GP-ADEIM's first steps) and every reduced model's (online `simulate`)
/// integrate through it. After every step (and at step 0) the observer sees the state, then the
/// adaptive hook (GP-ADEIM's update) may change the model. A Newton failure or a non-finite state
/// ends the run with status `diverged` and its reason: a result, not an exception (callers for
/// which a failure is an error, the reference and the training, say so with the reason). The
/// observer's time is measured apart from the loop's (the online time), the adaptive hook's is
/// online time.
#include <Teuchos_Time.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "gphr/core/DenseTypes.hpp"
#include "gphr/core/Error.hpp"
#include "gphr/core/RunStatus.hpp"
#include "gphr/core/Types.hpp"
#include "gphr/timeint/Integrator.hpp"

namespace gphr {

/// The outcome and costs of one time loop.
struct SimulationStats {
  RunStats run;                 ///< Newton and time-loop statistics
  double onlineSeconds = 0.0;   ///< the loop's wall seconds without the observer's share (the adaptive hook counts)
  double observeSeconds = 0.0;  ///< the observer's seconds
  RunStatus status = RunStatus::Ok;  ///< Ok, or Diverged (the loop decides no other)
  std::string reason;           ///< why it diverged
  long lastStep = 0;            ///< the last step whose state was observed
  /// A query's error indicator eta and its calibrated estimate of E_L2 (hyper/ErrorIndicator.hpp,
  /// doc/error-estimate.md): NaN where the model file has no indicator or calibration, or the run
  /// did not reach its end. indicatorSeconds: the indicator's share of onlineSeconds.
  /// @{
  double errorIndicator = std::numeric_limits<double>::quiet_NaN();
  double errorEstimate = std::numeric_limits<double>::quiet_NaN();
  double indicatorSeconds = 0.0;
  /// @}
  bool ok() const { return status == RunStatus::Ok; }  ///< it ran to the end
};

/// Whether every entry of a state is finite (dense: entry by entry; distributed: its norm, collective).
bool allFinite(const DenseVector& z);
/// @copydoc allFinite(const DenseVector&)
bool allFinite(const Vector& y);
/// H at step j of a run whose observer evaluates it, checked: a non-finite Hamiltonian (the model
/// overflowing at its parameter while its state stays finite) ends the run as `diverged`, as a
/// non-finite state does, instead of an `ok` run with a NaN energy and a drift of 0.
inline double finiteHamiltonian(double H, long j) {
  if (!std::isfinite(H)) throw SolverError(detail::concat("non-finite Hamiltonian ", H, " at step ", j));
  return H;
}

/// The loop itself, for an integrator of timeint (DenseModelIntegrator, FullModelIntegrator) and its
/// state y, integrated in place over `steps` steps of size dt (see the file's description).
template <class Integrator, class State>
SimulationStats observedTimeLoop(Integrator& integ, State& y, double dt, long steps,
                                 const std::function<void(long, double, const State&)>& observe,
                                 const std::function<void(long, double, const State&)>& adapt = {}) {
  SimulationStats stats;
  Teuchos::Time wall("online"), obs("observe");
  wall.start();
  try {
    stats.run = integ.run(y, dt, steps, [&](long j, double t, const State& yj, const StepReport&) {
      obs.start(true);
      stats.lastStep = j;
      if (!allFinite(yj)) throw SolverError(detail::concat("non-finite state at step ", j));
      if (observe) observe(j, t, yj);
      stats.observeSeconds += obs.stop();
      if (adapt) adapt(j, t, yj);
    });
  } catch (const SolverError& e) {
    stats.status = RunStatus::Diverged;
    stats.reason = e.what();
    if (obs.isRunning()) stats.observeSeconds += obs.stop();
  }
  stats.onlineSeconds = wall.stop() - stats.observeSeconds;
  return stats;
}

}  // namespace gphr
