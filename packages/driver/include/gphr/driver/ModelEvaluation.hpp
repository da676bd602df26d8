#pragma once
/// @file
/// Evaluation of a reduced or hyper-reduced model against the full model, shared by every method
/// of `gphr run` (rom, gp-deim, deim, sdeim): integrate z from 0 (the shifted initial state) with
/// the configured IMR/AVF, lift y = y0 + A z, and measure the paper's errors eq:errNR at the
/// saved steps, the Hamiltonian of the lift and the model's own Hamiltonian at every step.
/// A Newton failure or a non-finite state ends the run with status "diverged" and its step:
/// a result of the report, not a failure of `gphr`; a run that reaches the end but leaves the full
/// model's range is "unbounded" (RunStatus.hpp). Either way E_L2 and the times are reported.
#include <functional>

#include "gphr/driver/FomStage.hpp"
#include "gphr/driver/ModelRun.hpp"
#include "gphr/driver/RunContext.hpp"
#include "gphr/reduction/SymplecticBasis.hpp"
#include "gphr/online/RunStatus.hpp"
#include "gphr/online/TimeLoop.hpp"
#include "gphr/hyper/GpAdeimModel.hpp"
#include "gphr/core/DenseHamiltonian.hpp"

namespace gphr {

/// The k values of the reduced stages: pipeline.k (or reduction.k; 0 means the basis' own k).
std::vector<int> stageK(const Teuchos::ParameterList& cfg, const ReducedBasis& basis);

/// hasHamiltonian: the model has one (rom, gp-deim, gp-adeim); the classic DEIM baselines do not.
/// adapt: called after every step (and at step 0) once the state was measured, in online time
/// (GP-ADEIM's update, adeimUpdateHook).
ModelRun evaluateReducedModel(const RCP<const Comm>& comm, const EvaluationSettings& settings, const FomResult& fom,
                              const HamiltonianSystem& system, const MultiVector& A, DenseHamiltonian& model,
                              bool hasHamiltonian, const std::string& method, int k, int m, bool keepStates = false,
                              const StepHook& adapt = {});

}  // namespace gphr
