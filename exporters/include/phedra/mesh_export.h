#pragma once
// Static meshes of a design at one t through OpenMesh: OBJ and PLY (quads,
// shared vertices welded for merged designs).

#include "phedra/design.h"

#include <string>

namespace phedra {

/// The mesh at t as text in the format of `extension` (".obj" or ".ply").
/// Throws Error(internal) rather than write a non-finite number.
std::string mesh_text(const Design& design, double t, const std::string& extension);

}  // namespace phedra
