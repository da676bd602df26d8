#pragma once
/// @file
/// The term-weight fits of one reduced size k (DESIGN.md "Term weights"): gp-eqp (non-negative
/// weights by NNLS, the budget m the number of terms) and gp-eqp-refit (GP-DEIM's terms, signed
/// least-squares weights), read from the artifacts cache (`/eqp/<method>_k<k>_m<m>`) when their
/// key matches, else fitted on one training system built on first need and cached.
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "gphr/hyper/EmpiricalQuadrature.hpp"
#include "gphr/offline/ArtifactsCache.hpp"
#include "gphr/offline/Training.hpp"

namespace gphr {

/// A fit with its diagnostics and where it came from.
struct CachedFit {
  QuadratureFit fit;             ///< terms, weights, residual, stop reason
  double exactResidual = 0.0;    ///< on the unsketched rows (= fit.residual without a sketch)
  bool cached = false;           ///< read from the cache
  double fitSeconds = 0.0;       ///< the NNLS / refit solve
  double trainingSeconds = 0.0;  ///< building the training system of this k (each fit stands for it)
};

/// The fits of one k (see the file's description).
class TermWeightFits {
 public:
  /// GP-DEIM's m terms (the refit's), asked only when a refit is not in the cache.
  using DeimTerms = std::function<std::vector<GO>(int m)>;
  /// budgets: every m a caller may ask for (one greedy NNLS path serves them all); tolerance: the
  /// NNLS stopping tolerance; nnlsKey / refitKey: what each method's fits depend on (cache keys,
  /// completed with k and m); the cache is copied. Nothing is computed before get().
  TermWeightFits(const Scene& scene, RCP<const Comm> comm, const TrainingResult& training, const MultiVector& A,
                 const QuadratureOptions& options, double tolerance, std::vector<int> budgets,
                 DeimTerms deimTerms, const ArtifactsCache* cache = nullptr, std::string nnlsKey = "",
                 std::string refitKey = "");
  /// The fit of `method` (gp-eqp or gp-eqp-refit) with budget m. InputError when the training
  /// cannot support it (e.g. fewer candidate terms than m). Collective.
  CachedFit get(const std::string& method, int m);
  /// The fits of every m in ms; one the training cannot support is left out, its reason in `skipped`.
  std::map<int, QuadratureFit> all(const std::string& method, const std::vector<int>& ms,
                                   std::map<int, std::string>& skipped);

 private:
  std::string name(const std::string& method, int m) const;
  std::string key(const std::string& method, int m) const;
  bool read(const std::string& method, int m, CachedFit& out);
  void store(const std::string& method, int m, const CachedFit& c) const;
  CachedFit& finish(const std::string& method, int m, CachedFit& out);
  const SystemSet& systems();
  const QuadratureTraining& training();

  const Scene& scene_;
  RCP<const Comm> comm_;
  const TrainingResult& snapshots_;
  const MultiVector& A_;
  int k_;
  QuadratureOptions opt_;
  double tolerance_;
  std::vector<int> budgets_;
  DeimTerms deimTerms_;
  std::optional<ArtifactsCache> cache_;  // a copy: the caller's may go first
  std::string nnlsKey_, refitKey_;
  SystemSet systems_;
  QuadratureTraining training_;
  double trainingSeconds_ = 0.0;
  std::map<int, QuadratureFit> computed_;  // gp-eqp fits of the current path not yet returned
};

}  // namespace gphr
