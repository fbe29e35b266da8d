#pragma once
// The shape of a planar quadrilateral panel: convex, non-convex (one reflex
// corner, a "dart"), a bow-tie (two opposite edges cross: not a panel one can
// cut) or degenerate (no area). Motion preserves panel shapes, so one look at t*
// decides for the whole flexion interval.

#include "phedra/triangle_overlap.h"

#include <array>
#include <string>

namespace phedra {

enum class PanelShape { convex, non_convex, bow_tie, degenerate };

std::string to_string(PanelShape shape);

/// Corners in mesh order (0, 1, 2, 3).
using PanelCorners = std::array<Vec3, 4>;

PanelShape panel_shape(const PanelCorners& corners);

/// True for convex and non-convex panels.
inline bool is_valid_panel(PanelShape shape) { return shape == PanelShape::convex || shape == PanelShape::non_convex; }

/// The two triangles of a valid panel, split along the diagonal that lies inside
/// it (the one through the reflex corner of a non-convex panel).
std::array<Triangle, 2> panel_triangles(const PanelCorners& corners);

}  // namespace phedra
