#pragma once
// A small ordered JSON object writer for summary.json (no JSON library in the dependency set;
// the summary is flat enough that this stays simple). Non-finite numbers are written as null.
#include <string>
#include <utility>
#include <vector>

namespace gphr {

class JsonObject {
 public:
  JsonObject& set(const std::string& key, double value);
  JsonObject& set(const std::string& key, long value);
  JsonObject& set(const std::string& key, int value) { return set(key, static_cast<long>(value)); }
  JsonObject& set(const std::string& key, const std::string& value);
  JsonObject& set(const std::string& key, const char* value) { return set(key, std::string(value)); }
  JsonObject& set(const std::string& key, bool value);
  JsonObject& set(const std::string& key, const JsonObject& value);
  JsonObject& set(const std::string& key, const std::vector<JsonObject>& values);
  JsonObject& set(const std::string& key, const std::vector<double>& values);  // an array of numbers
  std::string str(int indent = 0) const;
  // Read back a number set earlier (the report's tables): NaN when absent, null or not a number.
  double number(const std::string& key) const;

 private:
  JsonObject& raw(const std::string& key, std::string json);
  std::vector<std::pair<std::string, std::string>> entries_;
};

std::string jsonString(const std::string& s);

}  // namespace gphr
