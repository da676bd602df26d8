#pragma once
/// @file
/// GPHR's exceptions (InputError, SolverError) and the GPHR_REQUIRE check that throws them.
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace gphr {

/// Bad input from a user (configuration, file, size mismatch): the message names the offending
/// value and what is allowed.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A numerical solver failed (Newton did not converge, linear solve broke down): the message
/// names where (step, time) and how (residual norm).
class SolverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

namespace detail {
/// A double as a message shows it: the fewest digits, 12 to 17, that read back as the same number,
/// so that a value 1 ulp outside a bound is not printed as the bound (0.89999999999999991, not 0.9).
struct Shortest {
  double x;
};
inline std::ostream& operator<<(std::ostream& os, Shortest s) {
  char buf[40];
  for (int digits = 12; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, s.x);
    if (std::strtod(buf, nullptr) == s.x) break;
  }
  return os << buf;
}
template <class T>
decltype(auto) shown(const T& x) {
  if constexpr (std::is_floating_point_v<T>) return Shortest{static_cast<double>(x)};
  else return (x);
}
/// The message parts as one string, doubles as Shortest shows them.
template <class... Args>
std::string concat(const Args&... args) {
  std::ostringstream os;
  os.precision(12);  // doubles inside other types (arrays, entries)
  (os << ... << shown(args));
  return os.str();
}
}  // namespace detail

}  // namespace gphr

/// GPHR_REQUIRE(cond, ErrorType, message parts...): throw ErrorType(concat(parts)) unless cond.
#define GPHR_REQUIRE(cond, ErrorType, ...)                        \
  do {                                                            \
    if (!(cond)) throw ErrorType(::gphr::detail::concat(__VA_ARGS__)); \
  } while (0)
