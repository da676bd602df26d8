#pragma once
/// @file
/// A stage's cache key: the options its results depend on, written as "name = value" lines with
/// its algorithm's revision, so that two keys are equal exactly when the stage would compute the
/// same thing. Each stage writes its own (trainingCacheKey beside TrainingOptions, ...), listing
/// every option that changes its results and leaving out those that only change who computes what
/// (group sizes, progress). Doubles are written with 17 significant digits: a key reads back the
/// value it was made from.
#include <string>
#include <vector>

namespace gphr {

/// A stage's key as "name = value" lines (see the file's description).
class CacheKey {
 public:
  /// A key of `stage` at algorithm `revision`: a change of the algorithm that changes its results
  /// bumps the revision, and every result cached under an older one is computed again.
  CacheKey(const std::string& stage, int revision);
  /// Appends the line "name = value" (text as it is, numbers as described above, lists in brackets).
  /// @{
  CacheKey& add(const std::string& name, const std::string& value);
  CacheKey& add(const std::string& name, const char* value) { return add(name, std::string(value)); }
  CacheKey& add(const std::string& name, double value);
  CacheKey& add(const std::string& name, long value);
  CacheKey& add(const std::string& name, int value) { return add(name, static_cast<long>(value)); }
  CacheKey& add(const std::string& name, unsigned long long value);
  CacheKey& add(const std::string& name, bool value) { return add(name, std::string(value ? "true" : "false")); }
  CacheKey& add(const std::string& name, const std::vector<double>& values);
  CacheKey& add(const std::string& name, const std::vector<int>& values);
  /// @}
  /// The key's text: one line per option, after a line naming the stage and revision.
  const std::string& str() const { return text_; }

 private:
  std::string text_;
};

}  // namespace gphr
