#pragma once
/// @file
/// Full-model references kept on disk, on ArtifactsCache's keyed-dataset rule: a reference is
/// read back only where its datasets carry the key of what would be run now (the scene's and the
/// integrator's configuration, the parameter, T, dt, the saved steps, the gphr version) and the
/// `complete` mark, and its data match their fingerprint (the states) and checksum (H). A file
/// that is damaged, of another scene or of another size is replaced, not trusted. One file per
/// reference, so that rank groups running different parameters never share a writer.
#include <string>

#include "gphr/evaluation/FullModelReference.hpp"

namespace gphr {

/// The full model at `mu` from the file at `path` when it holds it under `key` (see the file's
/// description), else run (runFullModel) and stored there; `cached` (if given) says which.
/// Collective over `comm`.
FullModelReference cachedFullModel(const std::string& path, const std::string& key, const EvaluationSettings& settings,
                                   const Scene& scene, const std::vector<double>& mu, const RCP<const Comm>& comm,
                                   bool* cached = nullptr);

}  // namespace gphr
