#pragma once
// The reduced-model stages of `gphr run` (issue: offline training and Galerkin ROM):
//   train  - full model over the training set; shifted snapshots of each parameter go to
//            DIR/artifacts.h5 /training/p<j> as soon as it finishes (resumable, see Training);
//   reduce - symplectic basis from all snapshots, cached in /basis with its provenance;
//   rom    - the Galerkin ROM at the test parameter, errors eq:errNR against the full model.
#include <string>
#include <vector>

#include "gphr/driver/FomStage.hpp"
#include "gphr/driver/RunContext.hpp"
#include "gphr/reduction/SymplecticBasis.hpp"

namespace gphr {

struct TrainingResult {
  std::vector<std::vector<double>> parameters;
  std::vector<RCP<const MultiVector>> snapshots;  // shifted states per training parameter
  long reused = 0;                                 // parameters taken from the file
  double seconds = 0.0;
};

struct RomStages {
  TrainingResult training;
  ReducedBasis basis;
  bool basisCached = false;
  double basisSeconds = 0.0;
  std::vector<double> hamiltonian, errors;  // H(y0 + A z^j) per step; ||y^j - y(z^j)|| at saved steps
  JsonObject run;                           // the "rom" entry of summary.json
};

// Resumable training: a parameter whose dataset is complete in the file is reused, one without
// its `complete` mark (killed mid-write) is redone. A file of another scene or size is an
// InputError naming the file; a changed training config starts the training over.
TrainingResult runTraining(const RunContext& ctx);
ReducedBasis runReduction(const RunContext& ctx, const TrainingResult& training, bool& cached);
// Galerkin ROM at the test parameter; errors against the full model's saved states.
void runRom(const RunContext& ctx, const FomResult& fom, RomStages& stages);

}  // namespace gphr
