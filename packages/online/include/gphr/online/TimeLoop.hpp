#pragma once
/// @file
/// A dense model's run through the one observed time loop (timeint/ObservedTimeLoop.hpp): the
/// settings of a run (dt, steps, the integrator section), `simulate` and GP-ADEIM's update as its
/// adaptive hook. `gphr run`'s evaluation of every reduced method, `gphr query`, `gphr validate`
/// and an embedding code's OnlineModel::simulate integrate through it.
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_Time.hpp>
#include <cmath>
#include <functional>
#include <string>

#include "gphr/core/DenseHamiltonian.hpp"
#include "gphr/core/Types.hpp"
#include "gphr/timeint/ObservedTimeLoop.hpp"

namespace gphr {

class GpAdeimModel;

/// The number of steps T / dt; InputError naming T and dt unless dt > 0, T >= dt and T is a whole
/// number of steps (to 1e-9 relative).
long wholeSteps(double T, double dt);

/// What a time loop runs: the step, the number of steps, and the integrator's settings.
struct SimulationSettings {
  double dt = 0.0;                         ///< the time step
  long steps = 0;                          ///< steps from t = 0 (T = steps dt)
  Teuchos::ParameterList integrator;       ///< the validated `integrator` section (scheme, Newton)
  int polynomialDegree = 0;                ///< of the nonlinear term (AVF's exact quadrature), 0 unknown
};

/// Called after each step j (and at j = 0) with t_j and z^j.
using StepHook = std::function<void(long, double, const DenseVector&)>;

/// Integrates `model` from z = 0 over settings.steps steps (see the file's description); z holds
/// the last state reached.
SimulationStats simulate(DenseHamiltonian& model, const SimulationSettings& settings, DenseVector& z,
                         const StepHook& observe = {}, const StepHook& adapt = {});

/// GP-ADEIM's update after step j as an adaptive hook: a degenerate update mid-run (InputError from
/// the update) is reported as the run's divergence, as any other failure of the online model.
StepHook adeimUpdateHook(GpAdeimModel& model);

}  // namespace gphr
