#pragma once
/// @file
/// The method registry: every reduced-model method GPHR knows, by the name configs, model files,
/// reports and queries use, with what distinguishes it. Code asks the registry (isStorable,
/// needsFullResidual, ...) instead of comparing method names.
#include <string>
#include <vector>

namespace gphr {

/// One method of the registry.
struct MethodInfo {
  const char* name;        ///< its name: fom, rom, gp-deim, gp-adeim, deim, sdeim, gp-eqp, gp-eqp-refit
  const char* summary;     ///< one line: what it is
  bool hyperReduced;       ///< it takes a DEIM size or term budget m (pipeline.m)
  bool storable;           ///< a reduced-model file (gphr build) can hold it
  bool needsFullResidual;  ///< online it samples the full residual, so its queries build the full system
  bool termWeights;        ///< its online model is a weighted sum of sampled terms (GpDeimModel)
  const char* fromFile;    ///< what a query reads of it from the model file ("" if not storable)
};

/// The methods' names, for code that picks one (the registry below says what each is).
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
/// Whether a method of this name exists.
bool isMethod(const std::string& name);
/// The names of the methods for which `pred` holds, joined by ", " (for messages and help texts).
std::string methodNames(bool (*pred)(const MethodInfo&) = nullptr);

}  // namespace gphr
