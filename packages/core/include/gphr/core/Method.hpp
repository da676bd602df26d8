#pragma once
/// @file
/// The method registry: every reduced-model method GPHR knows, by the name configs, model files,
/// reports and queries use, with what distinguishes it. A method is its registry entry: code asks
/// the entry what the method is (its reduction, its term-weight fit, whether a file can hold it)
/// and never compares names, so a new method is a new entry and the places its traits select.
/// It lives in core, below every package that builds, stores or reports a method.
#include <string>
#include <vector>

namespace gphr {

/// A method's identity; the entry's name is how files and configs spell it.
enum class MethodId { Fom, Rom, GpDeim, GpAdeim, Deim, Sdeim, GpEqp, GpEqpRefit };

/// How a method treats the nonlinear part of the Hamiltonian: decides how it is built, how it is
/// evaluated, and which of the report's tables and figures show it.
enum class Reduction {
  None,          ///< the full model (the reference of every error)
  Galerkin,      ///< all d terms projected: the ROM every hyper-reduced run is compared with at its k
  TermWeights,   ///< H_hr a weighted sum of m sampled terms (GpDeimModel): gp-deim, gp-eqp, gp-eqp-refit
  AdaptiveDeim,  ///< GP-DEIM whose DEIM basis is updated online from the full residual (alg:SP-ADEIM)
  GradientDeim,  ///< DEIM of the reduced gradient: a baseline without a Hamiltonian (deim, sdeim)
};

/// How a TermWeights method finds its weights.
enum class TermWeightFit {
  None,               ///< not a TermWeights method
  Deim,               ///< the DEIM weights of the reduced-Jacobian DEIM basis (sec:GP-DEIM)
  Nnls,               ///< non-negative weights by NNLS on the reduced gradients (gp-eqp)
  LeastSquaresRefit,  ///< GP-DEIM's terms, weights refit by least squares (gp-eqp-refit)
};

/// The DEIM basis a GradientDeim baseline interpolates the reduced gradient with.
enum class GradientBasis {
  None,          ///< not a GradientDeim method
  Snapshots,     ///< the POD of the gradient snapshots (the classic DEIM)
  ReducedBasis,  ///< U = A, the reduced basis itself (the structure-preserving DEIM, m = 2k)
};

/// One method of the registry.
struct MethodInfo {
  MethodId id;             ///< which method
  const char* name;        ///< its name: fom, rom, gp-deim, gp-adeim, deim, sdeim, gp-eqp, gp-eqp-refit
  const char* summary;     ///< one line: what it is
  Reduction reduction;     ///< how it treats the nonlinear term
  TermWeightFit fit;       ///< TermWeights methods: how the weights are found
  GradientBasis gradientBasis;  ///< GradientDeim baselines: the DEIM basis
  bool takesM;             ///< it takes a DEIM size or term budget m (pipeline.m)
  bool storable;           ///< a reduced-model file (gphr build) can hold it
  bool needsFullResidual;  ///< online it samples the full residual, so its queries build the full system
  const char* fromFile;    ///< what a query reads of it from the model file ("" if not storable)
  /// A reduced model (not the full one).
  bool reduced() const { return reduction != Reduction::None; }
  /// A hyper-reduced model: reduced, and not the Galerkin ROM of all d terms.
  bool hyperReduced() const { return reduced() && reduction != Reduction::Galerkin; }
  /// It has a Hamiltonian of its own (H_r, H_hr); the DEIM baselines interpolate a field that is not a gradient.
  bool hasHamiltonian() const { return reduction != Reduction::GradientDeim; }
  /// Its online model adapts as it runs (GP-ADEIM's updates: their records, window and cost).
  bool adaptive() const { return reduction == Reduction::AdaptiveDeim; }
  /// Its weights come from an empirical-quadrature fit (gp-eqp, gp-eqp-refit).
  bool quadratureFit() const { return fit == TermWeightFit::Nnls || fit == TermWeightFit::LeastSquaresRefit; }
};

/// The methods' names, for code that names one (to build it, to label a record); what a method
/// is, the registry's entry says: compare traits, never these names.
namespace method {
inline constexpr char kFom[] = "fom";                  ///< the full model
inline constexpr char kRom[] = "rom";                  ///< the Galerkin reduced model
inline constexpr char kGpDeim[] = "gp-deim";           ///< gradient-preserving DEIM
inline constexpr char kGpAdeim[] = "gp-adeim";         ///< adaptive GP-DEIM
inline constexpr char kDeim[] = "deim";                ///< the classic DEIM (baseline)
inline constexpr char kSdeim[] = "sdeim";              ///< the structure-preserving DEIM (baseline)
inline constexpr char kGpEqp[] = "gp-eqp";             ///< non-negative term weights (NNLS)
inline constexpr char kGpEqpRefit[] = "gp-eqp-refit";  ///< GP-DEIM's terms, weights refit
}  // namespace method

/// Every method, in the order of the reports.
const std::vector<MethodInfo>& methodRegistry();
/// The method of this name; InputError naming it and the known names if there is none.
const MethodInfo& methodInfo(const std::string& name);
/// The entry of a method.
const MethodInfo& methodInfo(MethodId id);
/// Whether a method of this name exists.
bool isMethod(const std::string& name);
/// The names of the methods for which `pred` holds, joined by ", " (for messages and help texts).
std::string methodNames(bool (*pred)(const MethodInfo&) = nullptr);

}  // namespace gphr
