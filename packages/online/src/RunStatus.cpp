#include "gphr/online/RunStatus.hpp"

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

const char* runStatus(bool finished, bool available, long unboundedAt) {
  if (!finished) return available ? "diverged" : "unavailable";
  return unboundedAt >= 0 ? "unbounded" : "ok";
}

}  // namespace gphr
