#include "gphr/driver/RomStage.hpp"

#include "gphr/driver/ModelEvaluation.hpp"
#include "gphr/reduction/GalerkinRom.hpp"

namespace gphr {

void runRom(const RunContext& ctx, const FomResult& fom, RomStages& st) {
  auto inst = ctx.scene->instantiate(ctx.comm, ctx.mu, true);
  for (int k : stageK(ctx.config, st.basis)) {
    auto A = leadingBasis(st.basis, k);
    GalerkinRom rom(inst.system, A);
    ModelRun run = evaluateReducedModel(ctx.comm, evaluationSettingsFrom(ctx.config), fom, *inst.system, *A, rom, true,
                                        "rom", k, 0);
    run.run.set("basis", st.basis.method)
        .set("energy_captured", st.basis.energyCaptured)
        .set("training_parameters", static_cast<long>(st.training.parameters.size()))
        .set("training_reused", st.training.reused)
        .set("basis_cached", st.basisCached)
        .set("t_offline_s", st.training.seconds + st.basisSeconds);
    setBasisKeys(ctx, st, run.run);
    st.runs.push_back(std::move(run));
  }
}

}  // namespace gphr
