#pragma once
/// @file
/// The hyper-reduction stage of `gphr run` (paper Sec. 3 and the Sec. 5.2 baselines): for every k
/// of the pipeline and every m, the hyper-reduced models of pipeline.methods (gp-deim, gp-eqp,
/// gp-eqp-refit, gp-adeim, deim, sdeim) built from the offline stages and evaluated like the
/// reduced model. Offline time is split by stage in each run's summary entry.
#include "gphr/driver/FomStage.hpp"
#include "gphr/driver/OfflineStages.hpp"

namespace gphr {

/// The hyper-reduced models of pipeline.methods for every k and m; appended to stages.runs.
void runHyperReduction(const RunOptions& options, const FomResult& fom, RomStages& stages);

}  // namespace gphr
