#pragma once
/// @file
/// GPHR's exceptions (InputError, SolverError) and the GPHR_REQUIRE check that throws them.
#include <sstream>
#include <stdexcept>
#include <string>

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
template <class... Args>
std::string concat(const Args&... args) {
  std::ostringstream os;
  os.precision(12);
  (os << ... << args);
  return os.str();
}
}  // namespace detail

}  // namespace gphr

/// GPHR_REQUIRE(cond, ErrorType, message parts...): throw ErrorType(concat(parts)) unless cond.
#define GPHR_REQUIRE(cond, ErrorType, ...)                        \
  do {                                                            \
    if (!(cond)) throw ErrorType(::gphr::detail::concat(__VA_ARGS__)); \
  } while (0)
