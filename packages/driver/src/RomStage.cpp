#include "gphr/driver/RomStage.hpp"

#include "gphr/driver/ModelEvaluation.hpp"
#include "gphr/reduction/GalerkinRom.hpp"
#include "gphr/core/Method.hpp"

namespace gphr {

void runRom(const RunContext& ctx, const FomResult& fom, RomStages& st) {
  auto inst = ctx.scene->instantiate(ctx.comm, ctx.mu, true);
  for (int k : stageK(ctx.config, st.basis)) {
    auto A = leadingBasis(st.basis, k);
    GalerkinRom rom(inst.system, A);
    ModelRun run = evaluateRun(evaluationSettingsFrom(ctx.config), fom, *inst.system, *A, rom, {method::kRom, k, 0, {}});
    run.metrics.set(Metric::Basis, st.basis.method)
        .set(Metric::EnergyCaptured, st.basis.energyCaptured)
        .set(Metric::TrainingParameters, static_cast<long>(st.training.parameters.size()))
        .set(Metric::TrainingReused, st.training.reused)
        .set(Metric::BasisCached, st.basisCached)
        .set(Metric::TOfflineS, st.training.seconds + st.basisSeconds);
    setBasisKeys(ctx, st, run.metrics);
    st.runs.push_back(std::move(run));
  }
}

}  // namespace gphr
