#pragma once
// One home for every tolerance. Lengths are relative to the model size L
// (the bounding-box diagonal), angles are sines, as MATH.md section 8 asks.

#include <algorithm>
#include <cmath>

namespace phedra::tolerance {

/// A healthy model keeps planarity, isometry and closure below this times L.
inline constexpr double check_relative = 1e-9;

/// |<d_i, axis>| <= orthogonality * |d_i| counts as orthogonal.
inline constexpr double orthogonality = 1e-9;
/// | |axis| - 1 | <= axis_unit.
inline constexpr double axis_unit = 1e-9;
/// Two profile planes are parallel when the sine of their angle is below this.
inline constexpr double parallel_sine = 1e-9;
/// A trajectory edge is parallel to a profile plane when the sine of their angle
/// is below this.
inline constexpr double edge_plane_sine = 1e-9;
/// Two points (or heights) coincide when closer than this times L.
inline constexpr double coincident = 1e-12;
/// A sigma- denominator smaller than this times L sends a vertex (near) infinity.
inline constexpr double vanishing_line = 1e-9;
/// Equal distances |S_0 - V| = |S_1 - V| (scissor case) up to this times L.
inline constexpr double scissor = 1e-12;
/// A configuration whose strip margin (1 - c^2, MATH.md section 4) is below this
/// counts as a bifurcation configuration.
inline constexpr double bifurcation_margin = 1e-12;

/// eps = max(rel * size, abs): a length tolerance scaled by the model size.
inline double scaled(double relative, double model_size, double absolute = 1e-300) {
  return std::max(relative * model_size, absolute);
}

}  // namespace phedra::tolerance
