#pragma once
/// @file
/// The fields of `gphr run` beside its numbers: which runs are shown (output.fieldModels), their
/// lifted states and pointwise differences to the full model in artifacts.h5, and fields.xdmf,
/// the ParaView view of them (output.xdmf). fields.png and spacetime.png: FieldPictures.hpp.
#include <optional>
#include <string>
#include <vector>

#include "gphr/driver/FieldModels.hpp"
#include "gphr/driver/FomStage.hpp"
#include "gphr/driver/OfflineStages.hpp"
#include "gphr/driver/RunContext.hpp"

namespace gphr {

class Hdf5File;

/// A run the field outputs show.
struct FieldRun {
  const ModelRun* run = nullptr;  ///< its summary (label, status)
  size_t group = 0;               ///< its index i in artifacts.h5's /runs/i
  std::shared_ptr<const FieldStates::Kept> kept;  ///< its lifted states, one per saved step
};

/// What the field outputs of a run show; the same on every rank.
struct FieldOutput {
  std::optional<SceneGrid> grid;   ///< the scene's grid; none: no field output (`notes` say why)
  std::vector<FieldRun> runs;      ///< the picked runs, in output.fieldModels' order
  std::vector<std::string> notes;  ///< lines for stderr: a scene without a grid, a name that picks no run
};

/// The field output of a finished run: empty unless output.plots or output.xdmf asks for fields.
FieldOutput fieldOutputOf(const RunOptions& options, const FomResult& fom, const RomStages* rom);

/// Collective: each picked run's states as /runs/i/states and their difference to the full model
/// as /runs/i/difference, (saved steps, 2n) like /fom/trajectory, one run at a time.
void writeFieldStates(Hdf5File& f, const FomResult& fom, const FieldOutput& out);

/// The text of fields.xdmf (XdmfWriter.hpp) over artifacts.h5: the full model's fields, each picked
/// run's and its difference to the full model (`<component>_<run>_minus_fom`), at the saved times.
std::string fieldsXdmf(const FomResult& fom, const FieldOutput& out);

}  // namespace gphr
