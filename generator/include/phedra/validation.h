#pragma once
// The assumptions of the construction (paper section 2, MATH.md sections 0-2)
// that can be checked on the control polylines alone. Each violated assumption
// throws InvalidInputError naming the field and index. The PHedron constructor
// calls validate() first and checks the rest (axial net, motion) itself.

#include "phedra/control_polylines.h"

namespace phedra {

/// The length scale of the input: bounding-box diagonal of the trajectory plus
/// the span of the apex heights. Tolerances of validation are relative to it.
double input_scale(const ControlPolylines& input);

/// Checks, in this order: counts (at least 2 profiles and 3 apexes, one
/// direction per trajectory point, n-1 signs), finite numbers, a unit axis,
/// non-zero directions orthogonal to the axis, distinct consecutive trajectory
/// points, a trajectory not orthogonal to the axis (T-hedron), pairwise distinct
/// consecutive apexes, consecutive profile planes neither parallel nor identical.
void validate(const ControlPolylines& input);

}  // namespace phedra
