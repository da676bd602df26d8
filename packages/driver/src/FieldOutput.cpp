#include "gphr/driver/FieldOutput.hpp"

#include "gphr/core/Error.hpp"
#include "gphr/driver/XdmfWriter.hpp"
#include "gphr/io/Hdf5File.hpp"
#include "gphr/core/Method.hpp"

namespace gphr {

FieldOutput fieldOutputOf(const RunOptions& opt, const FomResult& fom, const RomStages* rom) {
  FieldOutput out;
  if (!opt.output.plots && !opt.output.xdmf) return out;
  try {
    out.grid = fieldGrid(*opt.scene, static_cast<GO>(fom.trajectory->getGlobalLength()));
  } catch (const InputError& e) {
    out.notes.push_back(std::string("no fields.png, spacetime.png or fields.xdmf: ") + e.what());
    return out;
  }
  if (!rom || !fom.fieldStates) return out;
  out.notes = fom.fieldStates->notes();
  for (const auto& kept : fom.fieldStates->picked())
    for (size_t i = 0; i < rom->runs.size(); ++i)
      if (rom->runs[i].label() == kept->label) {
        out.runs.push_back({&rom->runs[i], i, kept});
        break;
      }
  return out;
}

void writeFieldStates(Hdf5File& f, const FomResult& fom, const FieldOutput& out) {
  const PhaseSpace ps(fom.trajectory->getGlobalLength() / 2, fom.trajectory->getMap()->getComm());
  for (const FieldRun& r : out.runs) {
    const std::string g = "/runs/" + std::to_string(r.group);
    const auto& kept = r.kept->states;
    MultiVector states(fom.trajectory->getMap(), kept.size());
    for (size_t j = 0; j < kept.size(); ++j) states.getVectorNonConst(j)->assign(*kept[j]);
    f.writeStates(g + "/states", states, ps);
    f.setAttribute(g + "/states", "layout", std::string("rows are the lifted states y0 + A z at /fom/times"));
    states.update(-1.0, *fom.trajectory, 1.0);
    f.writeStates(g + "/difference", states, ps);
    f.setAttribute(g + "/difference", "layout", std::string("rows are (y0 + A z) - y at /fom/times"));
  }
}

std::string fieldsXdmf(const FomResult& fom, const FieldOutput& out) {
  std::vector<XdmfStates> states{{method::kFom, "/fom/trajectory"}};
  for (const FieldRun& r : out.runs) {
    const std::string g = "/runs/" + std::to_string(r.group), name = fieldName(r.run->label());
    states.push_back({name, g + "/states"});
    states.push_back({name + "_minus_fom", g + "/difference"});
  }
  return xdmfText(*out.grid, "artifacts.h5", fom.savedTimes, states);
}

}  // namespace gphr
