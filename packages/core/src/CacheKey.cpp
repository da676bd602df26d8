#include "gphr/core/CacheKey.hpp"

#include <cstdio>

namespace gphr {

namespace {
std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}
}  // namespace

CacheKey::CacheKey(const std::string& stage, int revision) {
  text_ = "stage " + stage + ", revision " + std::to_string(revision) + "\n";
}

CacheKey& CacheKey::add(const std::string& name, const std::string& value) {
  text_ += name + " = " + value + "\n";
  return *this;
}

CacheKey& CacheKey::add(const std::string& name, double value) { return add(name, number(value)); }
CacheKey& CacheKey::add(const std::string& name, long value) { return add(name, std::to_string(value)); }
CacheKey& CacheKey::add(const std::string& name, unsigned long long value) { return add(name, std::to_string(value)); }

CacheKey& CacheKey::add(const std::string& name, const std::vector<double>& values) {
  std::string s = "[";
  for (size_t i = 0; i < values.size(); ++i) s += (i ? ", " : "") + number(values[i]);
  return add(name, s + "]");
}

CacheKey& CacheKey::add(const std::string& name, const std::vector<int>& values) {
  std::string s = "[";
  for (size_t i = 0; i < values.size(); ++i) s += (i ? ", " : "") + std::to_string(values[i]);
  return add(name, s + "]");
}

}  // namespace gphr
