#include "gphr/driver/RomStage.hpp"

#include "gphr/core/Progress.hpp"
#include "gphr/driver/ModelEvaluation.hpp"
#include "gphr/reduction/GalerkinRom.hpp"
#include "gphr/core/Method.hpp"

namespace gphr {

void runRom(const RunOptions& opt, const FomResult& fom, RomStages& st) {
  const SceneInstance& inst = st.offline->instance();
  for (int k : st.offline->sizes()) {
    const ProgressPhase phase("rom k = " + std::to_string(k));
    auto A = leadingBasis(st.basis, k);  // a copy: the ROM owns its basis
    GalerkinRom rom(inst.system, A);
    ModelRun run = evaluateRun(opt.evaluation, fom, *inst.system, *A, rom, {method::kRom, k, 0, {}});
    run.metrics.set(Metric::Basis, st.basis.method)
        .set(Metric::EnergyCaptured, st.basis.energyCaptured)
        .set(Metric::TrainingParameters, static_cast<long>(st.training.parameters.size()))
        .set(Metric::TrainingReused, st.training.reused)
        .set(Metric::BasisCached, st.basisCached)
        .set(Metric::TOfflineS, st.training.seconds + st.basisSeconds);
    setBasisKeys(opt, st, run.metrics);
    st.runs.push_back(std::move(run));
  }
}

}  // namespace gphr
