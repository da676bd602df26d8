#pragma once
/// @file
/// Scenes by name from a validated ParameterList. Keys depend on the scene: the valid list of
/// the `scene` and `parameters` sections is built for the chosen scene, with the parameter box as
/// the validators' ranges (so an out-of-box value is reported with the box).
#include <memory>

#include "gphr/models/Scene.hpp"

namespace gphr {

const Teuchos::Array<std::string>& sceneNames();  ///< nls1d, swe2d
/// Valid `scene` section for `name` (name, size key, shift), with paper defaults.
Teuchos::ParameterList sceneValidParameters(const std::string& name);
/// Valid `parameters` section: one key per box parameter, default = the paper's test parameter.
Teuchos::ParameterList sceneParameterValidParameters(const std::string& name);
/// Valid `time` section (T, dt) with the paper's defaults for the scene.
Teuchos::ParameterList sceneTimeValidParameters(const std::string& name);
/// The scene's defaults in a valid `integrator.linearSolver` section (its preconditioner: RELAXATION
/// on the SWE, where it is faster than the general default RILUK(1); doc/design.md).
void sceneLinearSolverDefaults(const std::string& name, Teuchos::ParameterList& linearSolver);

/// The scene of a validated `scene` section.
std::shared_ptr<Scene> makeScene(const Teuchos::ParameterList& sceneSection);
/// The parameter values of a validated `parameters` section, in the box's order.
std::vector<double> sceneParameters(const Scene& scene, const Teuchos::ParameterList& parameters);

}  // namespace gphr
