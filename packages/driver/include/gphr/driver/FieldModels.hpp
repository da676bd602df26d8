#pragma once
/// @file
/// Which evaluated models the field outputs of `gphr run` show beside the full model
/// (output.fieldModels), their lifted states while the runs are evaluated, and at which times
/// fields.png shows them (output.fieldTimes).
#include <memory>
#include <string>
#include <vector>

#include "gphr/driver/ModelRun.hpp"

namespace gphr {

/// Whether a run of `method` can be picked by one of `names` (`best`: every method but rom).
bool keepsFieldStates(const std::vector<std::string>& names, const std::string& method);

/// The lifted states the field outputs show, collected while the runs are evaluated: per name of
/// output.fieldModels, those of its most accurate (smallest E_L2) run so far among the runs that
/// ran to the end. The most accurate run is known only when all have run; a run superseded by a
/// more accurate one loses its states at once, so what is held stays O(names x saved states x
/// rows per rank) however many runs there are. Every rank decides alike (E_L2 is replicated).
class FieldStates {
 public:
  /// One kept run: its label (ModelRun::label), E_L2 and lifted states at the saved steps.
  struct Kept {
    std::string label;  ///< the run's label
    double eL2 = 0.0;   ///< its E_L2
    std::vector<RCP<Vector>> states;  ///< y0 + A z at the saved steps
  };
  /// The names of output.fieldModels and the number of saved states of a complete run.
  FieldStates(std::vector<std::string> names, size_t savedStates);
  /// Whether a run of `method` is to keep its lifted states for offer().
  bool wants(const std::string& method) const { return keepsFieldStates(names_, method); }
  /// Takes a finished run's states (run.states is left empty): kept for each name the run
  /// qualifies for and is the most accurate of so far, else dropped.
  void offer(ModelRun& run);
  /// The kept runs in the names' order, each once.
  std::vector<std::shared_ptr<const Kept>> picked() const;
  /// A line per name that kept no run ("output.fieldModels: ...").
  std::vector<std::string> notes() const;

 private:
  std::vector<std::string> names_;
  size_t saved_;
  std::vector<std::shared_ptr<const Kept>> best_;  ///< per name; null: none yet
};

/// The index of the saved time nearest to each of `times` (the first of two equally near).
std::vector<size_t> nearestSaved(const std::vector<double>& savedTimes, const std::vector<double>& times);

}  // namespace gphr
