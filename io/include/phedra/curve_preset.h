#pragma once
// The preset objects of smooth trajectories and direction rules (docs/presets.md,
// "Smooth trajectories"): {"helix": {...}} or {"spline": {...}} with
// "chord_tolerance", and {"rule": "normal" | "radial", ...}. The curves and rules
// themselves are geometry (smooth_trajectory.h); errors name the field, e.g.
// "trajectory.helix.radius".

#include "phedra/smooth_trajectory.h"

#include <nlohmann/json.hpp>

namespace phedra {

/// The curve of a trajectory object. `axis` is the preset's axis.
SmoothCurve smooth_curve(const nlohmann::json& trajectory, const Vec3& axis);

/// smooth_curve(...) discretized to its "chord_tolerance".
CurveSampling trajectory_curve(const nlohmann::json& trajectory, const Vec3& axis);

/// Directions by a rule object: {"rule": "normal", "angle_degrees": a} or
/// {"rule": "radial", "through": [x, y, z]} (smooth_trajectory.h says what each
/// gives). `tangents` may be empty: then they are the polyline's.
Points directions_by_rule(const nlohmann::json& rule, const Points& trajectory, Points tangents, const Vec3& axis);

}  // namespace phedra
