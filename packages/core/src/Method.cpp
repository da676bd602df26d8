#include "gphr/core/Method.hpp"

#include "gphr/core/Error.hpp"

namespace gphr {

const std::vector<MethodInfo>& methodRegistry() {
  using R = Reduction;
  using F = TermWeightFit;
  using G = GradientBasis;
  static const std::vector<MethodInfo> registry = {
      {MethodId::Fom, method::kFom, "the full model", R::None, F::None, G::None, false, false, false, ""},
      {MethodId::Rom, method::kRom, "the symplectic Galerkin reduced model (all d terms)", R::Galerkin, F::None, G::None,
       false, false, false, ""},
      {MethodId::GpDeim, method::kGpDeim, "gradient-preserving DEIM: DEIM weights on m sampled terms (sec:GP-DEIM)",
       R::TermWeights, F::Deim, G::None, true, true, false, "its sample mesh and DEIM weights"},
      {MethodId::GpAdeim, method::kGpAdeim, "GP-DEIM with online low-rank updates of the DEIM basis (alg:SP-ADEIM)",
       R::AdaptiveDeim, F::None, G::None, true, true, true, "its options; the basis A (build.withBasis)"},
      {MethodId::Deim, method::kDeim, "the classic DEIM of the reduced gradient (a baseline; not Hamiltonian)",
       R::GradientDeim, F::None, G::Snapshots, true, false, false, ""},
      {MethodId::Sdeim, method::kSdeim, "the structure-preserving DEIM of the gradient with U = A (a baseline; m = 2k)",
       R::GradientDeim, F::None, G::ReducedBasis, false, false, false, ""},
      {MethodId::GpEqp, method::kGpEqp, "non-negative term weights by NNLS on the reduced gradients (m: the term budget)",
       R::TermWeights, F::Nnls, G::None, true, true, false, "its sample mesh and term weights"},
      {MethodId::GpEqpRefit, method::kGpEqpRefit, "GP-DEIM's terms with weights refit by least squares",
       R::TermWeights, F::LeastSquaresRefit, G::None, true, true, false, "its sample mesh and term weights"},
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

const MethodInfo& methodInfo(MethodId id) {
  for (const auto& m : methodRegistry())
    if (m.id == id) return m;
  throw std::logic_error("a MethodId without a registry entry");
}

std::string methodNames(bool (*pred)(const MethodInfo&)) {
  std::string out;
  for (const auto& m : methodRegistry())
    if (!pred || pred(m)) out += (out.empty() ? "" : ", ") + std::string(m.name);
  return out;
}

}  // namespace gphr
