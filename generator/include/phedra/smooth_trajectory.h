#pragma once
// Semi-discrete input (issue 7, item 5): a smooth trajectory, a helix about the
// preset's axis or a clamped B-spline, discretized into the trajectory polyline
// with the fewest evenly spaced parameter values whose chords all stay within a
// stated tolerance of the curve; and direction rules that give one profile
// direction per trajectory point (for a curve, whose point count the user does
// not know). docs/presets.md, "Smooth trajectories".

#include "phedra/vector_types.h"

#include <nlohmann/json.hpp>

#include <functional>
#include <string>

namespace phedra {

/// A parametrised curve on u in [0, 1]: its point and tangent (derivative).
struct SmoothCurve {
  std::string kind;  ///< "helix" or "B-spline of degree d"
  std::function<Vec3(double)> point;
  std::function<Vec3(double)> tangent;
};

/// The discretized curve.
struct CurveSampling {
  Points points;            ///< the trajectory polyline (curve points at evenly spaced u)
  Points tangents;          ///< the curve's tangent at each of them
  double tolerance = 0.0;   ///< the chord tolerance asked for
  double deviation = 0.0;   ///< the largest distance of the curve from its chord (measured)
  std::string kind;
};

/// Largest number of segments a tolerance may ask for.
inline constexpr std::size_t max_curve_segments = 100000;

/// Evenly spaced u with the fewest segments such that every chord stays within
/// `tolerance` of the curve (measured at 32 points per chord). InvalidInputError
/// naming `field` when that would take more than max_curve_segments.
CurveSampling discretize(const SmoothCurve& curve, double tolerance, const std::string& field);

/// The curve of a trajectory object: {"helix": {...}} or {"spline": {...}}, with
/// "chord_tolerance". `axis` is the preset's (unit) axis. Errors name the field,
/// e.g. "trajectory.helix.radius".
SmoothCurve smooth_curve(const nlohmann::json& trajectory, const Vec3& axis);

/// smooth_curve(...) discretized to its "chord_tolerance".
CurveSampling trajectory_curve(const nlohmann::json& trajectory, const Vec3& axis);

/// Directions by a rule object: {"rule": "normal", "angle_degrees": a} (orthogonal
/// to the axis and to the tangent's part orthogonal to the axis, turned by a
/// about the axis) or {"rule": "radial", "through": [x, y, z]} (from the line
/// through that point along the axis to the trajectory point). `tangents` may be
/// empty: then they are the polyline's (central differences).
Points directions_by_rule(const nlohmann::json& rule, const Points& trajectory, Points tangents, const Vec3& axis);

}  // namespace phedra
