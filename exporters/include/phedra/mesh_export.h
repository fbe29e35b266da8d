#pragma once
// Static meshes of a design at one t through OpenMesh: OBJ and PLY (the
// distinct panels, face k = panel k; shared vertices welded).

#include "phedra/design.h"

#include <string>

namespace phedra {

/// The mesh at t as text in the format of `extension` (".obj" or ".ply");
/// `comment` (one line, may be empty) goes into the file as a comment (the
/// design's buildability). Throws Error(internal) rather than write a
/// non-finite number.
std::string mesh_text(const Design& design, double t, const std::string& extension, const std::string& comment = "");

}  // namespace phedra
