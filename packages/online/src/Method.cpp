#include "gphr/online/Method.hpp"

#include "gphr/core/Error.hpp"

namespace gphr {

const std::vector<MethodInfo>& methodRegistry() {
  static const std::vector<MethodInfo> registry = {
      {method::kFom, "the full model", false, false, false, false, ""},
      {method::kRom, "the symplectic Galerkin reduced model (all d terms)", false, false, false, false, ""},
      {method::kGpDeim, "gradient-preserving DEIM: DEIM weights on m sampled terms (sec:GP-DEIM)", true, true, false, true,
       "its sample mesh and DEIM weights"},
      {method::kGpAdeim, "GP-DEIM with online low-rank updates of the DEIM basis (alg:SP-ADEIM)", true, true, true, false,
       "its options; the basis A (build.withBasis)"},
      {method::kDeim, "the classic DEIM of the reduced gradient (a baseline; not Hamiltonian)", true, false, false, false, ""},
      {method::kSdeim, "the structure-preserving DEIM of the gradient with U = A (a baseline; m = 2k)", false, false, false,
       false, ""},
      {method::kGpEqp, "non-negative term weights by NNLS on the reduced gradients (m: the term budget)", true, true, false,
       true, "its sample mesh and term weights"},
      {method::kGpEqpRefit, "GP-DEIM's terms with weights refit by least squares", true, true, false, true,
       "its sample mesh and term weights"},
  };
  return registry;
}

bool isMethod(const std::string& name) {
  for (const auto& m : methodRegistry())
    if (name == m.name) return true;
  return false;
}

const MethodInfo& methodInfo(const std::string& name) {
  for (const auto& m : methodRegistry())
    if (name == m.name) return m;
  throw InputError(detail::concat("unknown method '", name, "'; allowed: ", methodNames()));
}

std::string methodNames(bool (*pred)(const MethodInfo&)) {
  std::string out;
  for (const auto& m : methodRegistry())
    if (!pred || pred(m)) out += (out.empty() ? "" : ", ") + std::string(m.name);
  return out;
}

}  // namespace gphr
