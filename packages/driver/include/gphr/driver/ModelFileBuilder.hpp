#pragma once
/// @file
/// The contents of a reduced-model file (doc/model-file.md) from the offline results: what
/// `gphr build` writes, callable from a user's code with a basis and DEIM basis of its own.
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
};

/// The file's header for `scene` (instance: any shifted instance of it; supplies the degree of G).
ReducedModelData modelFileHeader(const Scene& scene, const SceneInstance& instance, const ModelFileOptions& options);

/// Adds the gp-deim models of reduced size k (A: 2n x 2k) for each m (U: the reduced-Jacobian DEIM
/// basis, d x >= max m) and the basis data of k: probe rows, the parameter interpolant with its
/// error measured between the nodes. Collective over instance's communicator (the interpolant
/// instantiates the full system at each node: an O(n k) projection each).
void addReducedBasis(ReducedModelData& data, const Scene& scene, const SceneInstance& instance, const MultiVector& A,
                     int k, const MultiVector& U, const std::vector<int>& ms, const ModelFileOptions& options);

}  // namespace gphr
