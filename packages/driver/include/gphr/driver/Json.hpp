#pragma once
/// @file
/// A small ordered JSON object writer for summary.json (no JSON library in the dependency set;
/// the summary is flat enough that this stays simple). Non-finite numbers are written as null.
#include <string>
#include <utility>
#include <vector>

namespace gphr {

/// An ordered JSON object (key order as set), written as text by str().
class JsonObject {
 public:
  JsonObject& set(const std::string& key, double value);  ///< Sets `key` to a number (null if not finite).
  JsonObject& set(const std::string& key, long value);  ///< Sets `key` to an integer.
  /// Sets `key` to an integer.
  JsonObject& set(const std::string& key, int value) { return set(key, static_cast<long>(value)); }
  JsonObject& set(const std::string& key, const std::string& value);  ///< Sets `key` to a string.
  /// Sets `key` to a string.
  JsonObject& set(const std::string& key, const char* value) { return set(key, std::string(value)); }
  JsonObject& set(const std::string& key, bool value);  ///< Sets `key` to a boolean.
  JsonObject& set(const std::string& key, const JsonObject& value);  ///< Sets `key` to a nested object.
  /// Sets `key` to an array of objects.
  JsonObject& set(const std::string& key, const std::vector<JsonObject>& values);
  JsonObject& set(const std::string& key, const std::vector<double>& values);  ///< an array of numbers
  std::string str(int indent = 0) const;  ///< The object as JSON text, indented by `indent` spaces.

 private:
  JsonObject& raw(const std::string& key, std::string json);
  std::vector<std::pair<std::string, std::string>> entries_;
};

/// `s` as a quoted, escaped JSON string.
std::string jsonString(const std::string& s);

}  // namespace gphr
