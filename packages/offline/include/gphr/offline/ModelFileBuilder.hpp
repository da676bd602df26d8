#pragma once
/// @file
/// The contents of a reduced-model file (doc/model-file.md) from the offline results: what
/// `gphr build` writes, callable from a user's code with a basis and DEIM basis of its own.
#include <Teuchos_ParameterList.hpp>

#include <string>
#include <vector>

#include "gphr/hyper/ReducedModelFile.hpp"
#include "gphr/models/Scene.hpp"

namespace gphr {

/// Options of the reduced-model file: probes, parameter interpolation, DEIM index rule, integrator.
struct ModelFileOptions {
  std::vector<GO> probes;      ///< state entries whose lifted values queries can report
  int interpolationNodes = 7;  ///< Chebyshev-Lobatto nodes per parameter (2..33)
  std::string indices = "deim";  ///< DEIM indices: deim | qdeim
  std::string integratorConfig;  ///< YAML of the integrator section (empty: the defaults)
  /// Degrees of freedom whose q and p entries carry the online error indicator (ErrorIndicator.hpp); 0: none.
  int indicatorDofs = 16;
  /// The error a query is held to (build.targetError; 0: none): stored, and queries whose
  /// estimate exceeds it are marked.
  double targetError = 0.0;
};

/// The options a `build` section sets (probes, interpolationNodes, indicatorDofs); the indices and the integrator's
/// YAML are the caller's (sections hyper and integrator).
ModelFileOptions modelFileOptionsFrom(const Teuchos::ParameterList& build);
/// The keys of a `build` section with their defaults, ranges and documentation.
Teuchos::ParameterList modelFileValidParameters();

/// The file's header for `scene` (instance: any shifted instance of it; supplies the degree of G).
ReducedModelData modelFileHeader(const Scene& scene, const SceneInstance& instance, const ModelFileOptions& options);

/// A term-weighted model (its H_hr = sum_i w_i G_i over the given rows of G, paper eq:Hyperred_model)
/// as stored: the sample mesh of `rows` with `weights`. Collective.
StoredHyperModel termModel(const SceneInstance& instance, const MultiVector& A, const std::string& method, int k,
                           int m, const std::vector<GO>& rows, const std::vector<double>& weights);

/// The gp-deim models of reduced size k (A: 2n x 2k) for each m: DEIM indices of U (the
/// reduced-Jacobian DEIM basis, d x >= max m) and their weights. Collective.
std::vector<StoredHyperModel> gpDeimModels(const SceneInstance& instance, const MultiVector& A, int k,
                                           const MultiVector& U, const std::vector<int>& ms, const std::string& indices);

/// Adds the models of reduced size k and the basis data of k: probe rows, the parameter
/// interpolants with their error measured between the nodes. Collective over instance's
/// communicator (the interpolants instantiate the full system at each node: an O(n k) projection each).
void addReducedBasis(ReducedModelData& data, const Scene& scene, const SceneInstance& instance, const MultiVector& A,
                     int k, std::vector<StoredHyperModel> models, const ModelFileOptions& options);

/// The gp-deim models and the basis data in one call (gpDeimModels, then addReducedBasis).
void addReducedBasis(ReducedModelData& data, const Scene& scene, const SceneInstance& instance, const MultiVector& A,
                     int k, const MultiVector& U, const std::vector<int>& ms, const ModelFileOptions& options);

}  // namespace gphr
