#pragma once
/// @file
/// A reduced model of `gphr run` or `gphr validate` evaluated against the full model: the
/// evaluation library's run (ReducedEvaluation.hpp) as a ModelRun, its failure or blow-up told
/// on the console, its lifted states offered to the field outputs.
#include "gphr/driver/FomStage.hpp"
#include "gphr/driver/ModelRun.hpp"
#include "gphr/reduction/SymplecticBasis.hpp"

namespace gphr {

/// Which run: its method (the registry says whether it has a Hamiltonian to observe), its sizes and
/// GP-ADEIM's update as the adaptive hook.
struct RunSpec {
  std::string method;      ///< a registry name
  int k = 0;               ///< reduced size
  int m = 0;               ///< DEIM size or term budget; 0 for rom
  StepHook adapt;          ///< after every step, in online time (adeimUpdateHook); none: the run is repeatable
};

/// Evaluates `model` on the shifted `system` with basis A against `fom` (see the file's description).
ModelRun evaluateRun(const EvaluationSettings& settings, const FomResult& fom, const HamiltonianSystem& system,
                     const MultiVector& A, DenseHamiltonian& model, const RunSpec& spec);

}  // namespace gphr
