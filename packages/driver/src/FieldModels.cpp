#include "gphr/driver/FieldModels.hpp"

#include <algorithm>
#include <cmath>

#include "gphr/core/Error.hpp"
#include "gphr/online/Method.hpp"

namespace gphr {

namespace {
bool notFom(const MethodInfo& m) { return std::string(m.name) != "fom"; }  // the full model is always shown
}  // namespace

std::vector<std::string> fieldModelNames(const Teuchos::ParameterList& cfg) {
  std::vector<std::string> out;
  for (const auto& name : cfg.sublist("output").get<Teuchos::Array<std::string>>("fieldModels")) {
    GPHR_REQUIRE(name == "best" || (isMethod(name) && name != "fom"), InputError, "key 'output.fieldModels' has entry '",
                 name, "'; allowed: best or one of ", methodNames(notFom));
    if (std::find(out.begin(), out.end(), name) == out.end()) out.push_back(name);
  }
  return out;
}

std::vector<double> fieldTimes(const Teuchos::ParameterList& cfg) {
  const double T = cfg.sublist("time").get<double>("T");
  const auto& given = cfg.sublist("output").get<Teuchos::Array<double>>("fieldTimes");
  if (given.empty()) return {0.0, 0.5 * T, T};
  for (double t : given)
    GPHR_REQUIRE(t >= 0.0 && t <= T, InputError, "key 'output.fieldTimes' has entry ", t, "; allowed: times in [0, ", T,
                 "] (time.T)");
  return {given.begin(), given.end()};
}

bool keepsFieldStates(const std::vector<std::string>& names, const std::string& method) {
  return std::any_of(names.begin(), names.end(), [&](const std::string& name) {
    // every method but the full and the Galerkin model is a hyper-reduction (sdeim too, whose m is fixed)
    return name == method || (name == "best" && method != "rom" && method != "fom");
  });
}

FieldRuns pickFieldRuns(const std::vector<std::string>& names, const std::vector<ModelRun>& runs, size_t savedStates) {
  FieldRuns out;
  for (const auto& name : names) {
    const ModelRun* best = nullptr;
    for (const auto& r : runs)
      if (r.ok && r.states.size() == savedStates && std::isfinite(r.eL2) && keepsFieldStates({name}, r.method) &&
          (!best || r.eL2 < best->eL2))
        best = &r;
    if (!best)
      out.notes.push_back("output.fieldModels: no run of '" + name + "' ran to the end; its fields are not shown");
    else if (std::find(out.runs.begin(), out.runs.end(), best) == out.runs.end())
      out.runs.push_back(best);
  }
  return out;
}

std::vector<size_t> nearestSaved(const std::vector<double>& savedTimes, const std::vector<double>& times) {
  std::vector<size_t> out;
  for (double t : times) {
    size_t j = 0;
    for (size_t i = 1; i < savedTimes.size(); ++i)
      if (std::abs(savedTimes[i] - t) < std::abs(savedTimes[j] - t)) j = i;
    out.push_back(j);
  }
  return out;
}

}  // namespace gphr
