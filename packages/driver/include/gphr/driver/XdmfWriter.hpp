#pragma once
/// @file
/// ParaView / VisIt output: the text of an XDMF 2 file over saved states already in an HDF5 file.
/// The states stay where they are (datasets of shape (times, 2n), HDF5File.hpp); the XDMF file
/// names, per time and per physical component, the hyperslab of the row and block that holds it,
/// on the scene's grid (a 3DCoRectMesh: ParaView shows 1-D and 2-D grids as flat 3-D ones).
#include <string>
#include <vector>

#include "gphr/models/Scene.hpp"

namespace gphr {

/// One dataset of saved states shown as fields: component c of row j is the field
/// "<component>_<name>" at the series' time j.
struct XdmfStates {
  std::string name;     ///< appended to each component's name: fom, rom_k10, gp-deim_k10_m20_minus_fom, ...
  std::string dataset;  ///< the HDF5 path of a (times, grid points x components) dataset
};

/// The scene's grid checked against the state size; InputError naming the scene when it declares
/// none (Scene::grid) or a grid that does not fit its states.
SceneGrid fieldGrid(const Scene& scene, GO fullDim);

/// A run's label as a field name: "gp-deim k=10 m=20" -> "gp-deim_k10_m20".
std::string fieldName(const std::string& label);

/// The XDMF 2 text of a temporal collection over `times`: every dataset of `states`, stored in
/// `h5File` (a path relative to the XDMF file), as node fields on `grid`.
std::string xdmfText(const SceneGrid& grid, const std::string& h5File, const std::vector<double>& times,
                     const std::vector<XdmfStates>& states);

}  // namespace gphr
