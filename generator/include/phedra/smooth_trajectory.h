#pragma once
// Semi-discrete input (issue 7, item 5): a smooth trajectory, a helix about the
// preset's axis or a clamped B-spline, discretized into the trajectory polyline
// with the fewest evenly spaced parameter values whose chords all stay within a
// stated tolerance of the curve; and direction rules that give one profile
// direction per trajectory point (for a curve, whose point count the user does
// not know). docs/presets.md, "Smooth trajectories". The preset objects that
// ask for them are read by io/ (curve_preset.h).

#include "phedra/vector_types.h"

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

/// A helix about `axis` (through `center`): `turns` turns of `radius`, rising
/// `rise_per_turn` along the axis per turn, starting at `start_angle_degrees`.
/// InvalidInputError naming "trajectory.helix.radius" / ".turns" for a radius or
/// turn count that is not positive, or above 1000 turns.
struct HelixSpec {
  Vec3 center = Vec3::Zero();
  double radius = 1.0;
  double rise_per_turn = 0.0;
  double turns = 1.0;
  double start_angle_degrees = 0.0;
  bool clockwise = false;
};
SmoothCurve helix_curve(const HelixSpec& spec, const Vec3& axis);

/// The clamped uniform B-spline of degree 1..7 on `control` (at least degree + 1
/// points; InvalidInputError naming "trajectory.spline.degree" / ".control_points").
SmoothCurve spline_curve(const Points& control, int degree);

/// One direction per trajectory point, orthogonal to the axis and to the
/// tangent's part orthogonal to the axis, turned by `angle_degrees` about the
/// axis. `tangents` may be empty: then they are the polyline's (central
/// differences). InvalidInputError ("directions.rule") where a tangent is
/// parallel to the axis.
Points normal_directions(const Points& trajectory, Points tangents, const Vec3& axis, double angle_degrees);

/// One direction per trajectory point: from the line through `through` along the
/// axis to the point (InvalidInputError "directions.through" for a point on it).
Points radial_directions(const Points& trajectory, const Vec3& through, const Vec3& axis);

}  // namespace phedra
