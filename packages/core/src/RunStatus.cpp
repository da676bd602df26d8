#include "gphr/core/RunStatus.hpp"

#include <cmath>

#include "gphr/core/Error.hpp"

namespace gphr {

UnboundedStep firstUnboundedStep(double H0, double fomMaxNorm, const std::vector<double>& hamiltonian,
                                 const std::vector<double>& stateNorms) {
  const double hCap = kUnboundedHamiltonian * std::abs(H0), normCap = kUnboundedNorm * fomMaxNorm;
  UnboundedStep out;
  for (size_t j = 0; j < hamiltonian.size() && j < stateNorms.size(); ++j) {
    const double dH = std::abs(hamiltonian[j] - H0);
    if (H0 != 0.0 && dH > hCap)
      out.reason = detail::concat("|H(y0 + A z^j) - H(y^0)| / |H(y^0)| = ", dH / std::abs(H0), " > ",
                                  kUnboundedHamiltonian);
    else if (stateNorms[j] > normCap)
      out.reason = detail::concat("||y0 + A z^j|| = ", stateNorms[j], " > ", kUnboundedNorm,
                                  " x the full model's largest ||y|| = ", fomMaxNorm);
    if (!out.reason.empty()) {
      out.step = static_cast<long>(j);
      return out;
    }
  }
  return out;
}

const char* statusName(RunStatus status) {
  switch (status) {
    case RunStatus::Ok: return "ok";
    case RunStatus::Unbounded: return "unbounded";
    case RunStatus::Diverged: return "diverged";
    case RunStatus::Unavailable: return "unavailable";
  }
  return "unknown";
}

RunStatus statusFromName(const std::string& name) {
  for (RunStatus s : {RunStatus::Ok, RunStatus::Unbounded, RunStatus::Diverged, RunStatus::Unavailable})
    if (name == statusName(s)) return s;
  throw InputError(detail::concat("status '", name, "'; allowed: ok, unbounded, diverged, unavailable"));
}

RunStatus runStatus(bool finished, bool available, long unboundedAt) {
  if (!finished) return available ? RunStatus::Diverged : RunStatus::Unavailable;
  return unboundedAt >= 0 ? RunStatus::Unbounded : RunStatus::Ok;
}

}  // namespace gphr
