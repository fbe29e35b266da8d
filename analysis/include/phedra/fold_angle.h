#pragma once
// The fold angle of a hinge in the FOLD convention (fold lines of the exports
// and of the cut sheets, mountain or valley).

#include "phedra/vector_types.h"

namespace phedra {

/// Fold angle in degrees of the hinge a-b between faces f (traversing a->b) and g,
/// from their unit normals: positive for a valley, negative for a mountain.
double fold_angle_degrees(const Vec3& normal_f, const Vec3& normal_g, const Vec3& a, const Vec3& b);

}  // namespace phedra
