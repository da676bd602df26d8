#pragma once
/// @file
/// FNV-1a, 64 bits: the checksums of the reduced-model file's data (ReducedModelFile.cpp) and of a
/// query's result file (QueryCommand.cpp). A fingerprint against changed bytes, not a
/// cryptographic signature; written out because neither Trilinos nor the C++ library has one.
#include <cstdio>
#include <string>
#include <vector>

namespace gphr {

/// FNV-1a over bytes in a fixed order; doubles by their bit patterns, strings and arrays with
/// their lengths first (so ("ab", "c") and ("a", "bc") differ).
class Fnv1a {
 public:
  /// Hashes `n` bytes at `p`.
  void bytes(const void* p, size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    for (size_t i = 0; i < n; ++i) h_ = (h_ ^ c[i]) * 1099511628211ULL;
  }
  void number(double x) { bytes(&x, sizeof x); }  ///< Hashes a double's bit pattern.
  /// Hashes a string: its length, then its bytes.
  void text(const std::string& s) {
    number(double(s.size()));
    bytes(s.data(), s.size());
  }
  /// Hashes an array: its length, then each entry as a double.
  template <class T>
  void numbers(const std::vector<T>& v) {
    number(double(v.size()));
    for (const auto& x : v) number(double(x));
  }
  /// "fnv1a64:" and the 16 hex digits of the hash.
  std::string hex() const {
    char buf[32];
    std::snprintf(buf, sizeof buf, "fnv1a64:%016llx", static_cast<unsigned long long>(h_));
    return buf;
  }

 private:
  unsigned long long h_ = 1469598103934665603ULL;
};

}  // namespace gphr
