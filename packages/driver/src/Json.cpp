#include "gphr/driver/Json.hpp"

#include <cstdlib>
#include <limits>

#include <cmath>
#include <sstream>

namespace gphr {

std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\', out += c;
    else if (c == '\n') out += "\\n";
    else if (static_cast<unsigned char>(c) < 0x20) out += ' ';
    else out += c;
  }
  return out + "\"";
}

JsonObject& JsonObject::raw(const std::string& key, std::string json) {
  for (auto& e : entries_)
    if (e.first == key) {
      e.second = std::move(json);
      return *this;
    }
  entries_.emplace_back(key, std::move(json));
  return *this;
}

JsonObject& JsonObject::set(const std::string& key, double value) {
  if (!std::isfinite(value)) return raw(key, "null");
  std::ostringstream os;
  os.precision(17);
  os << value;
  return raw(key, os.str());
}
JsonObject& JsonObject::set(const std::string& key, const std::vector<double>& values) {
  std::ostringstream os;
  os.precision(17);
  os << "[";
  for (size_t i = 0; i < values.size(); ++i) {
    if (i) os << ", ";
    if (std::isfinite(values[i])) os << values[i];
    else os << "null";
  }
  os << "]";
  return raw(key, os.str());
}
JsonObject& JsonObject::set(const std::string& key, long value) { return raw(key, std::to_string(value)); }
JsonObject& JsonObject::set(const std::string& key, const std::string& value) { return raw(key, jsonString(value)); }
JsonObject& JsonObject::set(const std::string& key, bool value) { return raw(key, value ? "true" : "false"); }
JsonObject& JsonObject::set(const std::string& key, const JsonObject& value) { return raw(key, value.str(2)); }
JsonObject& JsonObject::set(const std::string& key, const std::vector<JsonObject>& values) {
  std::string s = "[";
  for (size_t i = 0; i < values.size(); ++i) s += (i ? ", " : "") + values[i].str(2);
  return raw(key, s + "]");
}

std::string JsonObject::str(int indent) const {
  const std::string pad(indent, ' ');
  std::string s = "{";
  for (size_t i = 0; i < entries_.size(); ++i)
    s += (i ? ",\n" : "\n") + pad + "  " + jsonString(entries_[i].first) + ": " + entries_[i].second;
  return s + "\n" + pad + "}";
}

}  // namespace gphr
