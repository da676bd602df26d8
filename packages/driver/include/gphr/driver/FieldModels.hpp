#pragma once
/// @file
/// Which evaluated models the field outputs of `gphr run` show beside the full model
/// (output.fieldModels), and at which times fields.png shows them (output.fieldTimes).
#include <Teuchos_ParameterList.hpp>
#include <string>
#include <vector>

#include "gphr/driver/ModelRun.hpp"

namespace gphr {

/// output.fieldModels, checked: each entry a method of the registry or `best`.
std::vector<std::string> fieldModelNames(const Teuchos::ParameterList& cfg);
/// output.fieldTimes, checked against [0, time.T]; empty: the start, the middle and the end.
std::vector<double> fieldTimes(const Teuchos::ParameterList& cfg);
/// Whether a run of `method` can be among the picked ones, so its lifted states must be kept.
bool keepsFieldStates(const std::vector<std::string>& names, const std::string& method);

/// The runs the names pick, in their order and each once, with a note per name that picks none.
struct FieldRuns {
  std::vector<const ModelRun*> runs;  ///< the picked runs (states kept for every saved step)
  std::vector<std::string> notes;     ///< "output.fieldModels: ..." for each name without a run
};
/// Per name, the most accurate run (smallest E_L2) of that method, or of any hyper-reduced method
/// for `best`, among the runs that ran to the end and kept all `savedStates` states.
FieldRuns pickFieldRuns(const std::vector<std::string>& names, const std::vector<ModelRun>& runs, size_t savedStates);

/// The index of the saved time nearest to each of `times` (the first of two equally near).
std::vector<size_t> nearestSaved(const std::vector<double>& savedTimes, const std::vector<double>& times);

}  // namespace gphr
