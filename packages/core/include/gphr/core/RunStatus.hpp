#pragma once
/// @file
/// The status of a reduced or hyper-reduced run, decided once for `gphr run`, its console line,
/// runs.csv, report.md and summary.json:
/// - `ok`: it ran to the end and its lift stayed within the full model's range;
/// - `unbounded`: it ran to the end, but from some step j its lift y0 + A z^j left that range by
///   orders of magnitude:
///     |H(y0 + A z^j) - H(y^0)| > kUnboundedHamiltonian |H(y^0)|   or
///     ||y0 + A z^j||           > kUnboundedNorm max_i ||y^i||  (the full model's saved states);
/// - `diverged`: Newton failed or the state became non-finite before the end;
/// - `unavailable`: not run (the offline data cannot support its (k, m)).
/// The full model conserves H (to ~1e-8 relative with AVF on the paper's NLS) and, on NLS, the
/// mass ||y||^2; a bounded but inaccurate hyper-reduced run stays within a few times of them
/// (GP-DEIM at the paper's NLS, 2k = 400, m = 100: E_L2 1.4, relative H error 5.6), while a run
/// that blows up passes them by orders of magnitude (the classic DEIM of projected snapshots on
/// NLS n = 256, T = 50, AVF, 2k = 20, m = 20: relative H error ~1e11 where it runs to the end).
#include <string>
#include <vector>

namespace gphr {

/// Bounds of the status "unbounded": relative Hamiltonian and state-norm factors (see the file's
/// description).
/// @{
constexpr double kUnboundedHamiltonian = 1e3, kUnboundedNorm = 1e2;
/// @}

/// The first step at which a finished run left the full model's range.
struct UnboundedStep {
  long step = -1;      ///< the first such step j (the histories' index: step 0 is the initial state); -1: none
  std::string reason;  ///< which bound it passed, with the figures; empty when step is -1
};

/// The first j where |hamiltonian[j] - H0| > kUnboundedHamiltonian |H0| (skipped where H0 = 0) or
/// stateNorms[j] > kUnboundedNorm fomMaxNorm; histories indexed by step from 0, compared up to the
/// shorter of the two. Both bounds are strict: a value equal to its bound is within range.
UnboundedStep firstUnboundedStep(double H0, double fomMaxNorm, const std::vector<double>& hamiltonian,
                                 const std::vector<double>& stateNorms);

/// The status of a run (the file's description): one type for the time loop, the runs of `gphr
/// run`, queries and validation points; files and reports write it as its name.
enum class RunStatus {
  Ok,          ///< ran to the end, within the full model's range
  Unbounded,   ///< ran to the end, its lift out of the full model's range
  Diverged,    ///< Newton failed or the state or its H became non-finite
  Unavailable  ///< not run: the offline data cannot support its (k, m)
};
/// ok | unbounded | diverged | unavailable: the word every file and report writes.
const char* statusName(RunStatus status);
/// The status of a name statusName() gives; InputError naming the word and the names otherwise.
RunStatus statusFromName(const std::string& name);
/// The status of a run, as the file's description defines it.
RunStatus runStatus(bool finished, bool available, long unboundedAt);

}  // namespace gphr
