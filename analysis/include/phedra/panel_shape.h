#pragma once
// The shape of a planar quadrilateral panel: convex, non-convex (one reflex
// corner, a "dart"), a bow-tie (two opposite edges cross: not a panel one can
// cut) or degenerate (no area). Motion preserves panel shapes, so one look at t*
// decides for the whole flexion interval.

#include "phedra/triangle_overlap.h"

#include <array>
#include <string>

namespace phedra {

/// oversized and sliver: simple, but beyond the size bounds (panel_size.h); they
/// are not what panel_shape() returns, the buildability report sets them.
enum class PanelShape { convex, non_convex, bow_tie, degenerate, oversized, sliver };

std::string to_string(PanelShape shape);

/// Corners in mesh order (0, 1, 2, 3).
using PanelCorners = std::array<Vec3, 4>;

PanelShape panel_shape(const PanelCorners& corners);

/// The longest edge of a quad, squared: the scale of its shape tolerances.
double longest_edge_squared(const PanelCorners& corners);

/// The signed corner turns <e_{k-1} x e_k, normal> of a quad (corner k between
/// edge k - 1 and edge k, edge k from corner k to corner k + 1).
std::array<double, 4> corner_turns(const PanelCorners& corners, const Vec3& normal);

/// The unit normal of a quad from its largest corner cross product (zero for none).
Vec3 quad_normal(const PanelCorners& corners);

/// The shape class of a quad from its corner turns: all of one sign convex, three
/// to one non-convex, two to two crossed (a bow-tie); turns within `straight` of
/// zero count as positive; `degenerate` when no turn exceeds `flat`.
PanelShape shape_from_turns(const std::array<double, 4>& turns, double straight, double flat);

/// True for convex and non-convex panels.
inline bool is_valid_panel(PanelShape shape) { return shape == PanelShape::convex || shape == PanelShape::non_convex; }

/// The two triangles of a valid panel, split along the diagonal that lies inside
/// it (the one through the reflex corner of a non-convex panel).
std::array<Triangle, 2> panel_triangles(const PanelCorners& corners);

}  // namespace phedra
