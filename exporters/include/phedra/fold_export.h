#pragma once
// FOLD 1.2 (https://github.com/edemaine/fold) of a design: the mesh with its
// vertices at the first t, and the motion as `file_frames` that inherit the
// topology (`frame_inherit`) and give `vertices_coords`, `edges_foldAngle`
// (degrees; positive valley, negative mountain) and `edges_assignment` (M, V,
// F for flat hinges, B for boundary edges) at each further t.

#include "phedra/design.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace phedra {

/// The FOLD JSON text for the given t (at least one); `buildability` (when not
/// null) is stored as "phedra:buildability". Throws Error(internal) rather than
/// write a non-finite number.
std::string fold_json(const Design& design, const std::vector<double>& ts, const nlohmann::json& buildability = nullptr);

/// Fold angle in degrees of the hinge a-b between faces f (traversing a->b) and g,
/// from their unit normals: positive for a valley, negative for a mountain.
double fold_angle_degrees(const Vec3& normal_f, const Vec3& normal_g, const Vec3& a, const Vec3& b);

}  // namespace phedra
