#include "gphr/driver/FieldModels.hpp"

#include <algorithm>
#include <cmath>

#include "gphr/core/Error.hpp"
#include "gphr/core/Method.hpp"

namespace gphr {

bool keepsFieldStates(const std::vector<std::string>& names, const std::string& method) {
  return std::any_of(names.begin(), names.end(), [&](const std::string& name) {
    // "best": the most accurate hyper-reduction (sdeim too, whose m is fixed)
    return name == method || (name == "best" && methodInfo(method).hyperReduced());
  });
}

FieldStates::FieldStates(std::vector<std::string> names, size_t savedStates)
    : names_(std::move(names)), saved_(savedStates), best_(names_.size()) {}

void FieldStates::offer(ModelRun& run) {
  auto kept = std::make_shared<Kept>();
  kept->label = run.label(), kept->eL2 = run.eL2;
  kept->states.swap(run.states);
  if (!run.ok || kept->states.size() != saved_ || !std::isfinite(run.eL2)) return;  // stopped early: dropped
  for (size_t i = 0; i < names_.size(); ++i)
    if (keepsFieldStates({names_[i]}, run.method) && (!best_[i] || run.eL2 < best_[i]->eL2)) best_[i] = kept;
}

std::vector<std::shared_ptr<const FieldStates::Kept>> FieldStates::picked() const {
  std::vector<std::shared_ptr<const Kept>> out;
  for (const auto& b : best_)
    if (b && std::find(out.begin(), out.end(), b) == out.end()) out.push_back(b);
  return out;
}

std::vector<std::string> FieldStates::notes() const {
  std::vector<std::string> out;
  for (size_t i = 0; i < names_.size(); ++i)
    if (!best_[i]) out.push_back("output.fieldModels: no run of '" + names_[i] + "' ran to the end; its fields are not shown");
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
