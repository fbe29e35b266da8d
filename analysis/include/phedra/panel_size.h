#pragma once
// Whether a design's size can be built (issue 24). A panel far larger than the
// design's typical panel (two nearly parallel lines that meet far out) or a
// sliver (next to no width for its length) is simple, but nobody can cut it;
// a design that grows without bound towards a flexion limit cannot be built
// there. Panel shapes do not change with t (the motion is an isometry), so the
// panel bounds are decided at t*; the growth is followed along the motion.

#include "phedra/assembly_mesh.h"
#include "phedra/design.h"
#include "phedra/grid_topology.h"
#include "phedra/panel_shape.h"
#include "phedra/vector_types.h"

#include <array>
#include <cstddef>
#include <vector>

namespace phedra {

/// The documented bounds (docs/design.md, "Size-bounded buildability").
struct SizeBounds {
  /// The bounding-box diagonal at any buildable t at most this many times the
  /// one at t* (--max-growth; 0: no bound).
  double max_growth = 10.0;
  /// A panel's longest edge at most this many times the median longest edge of
  /// the design's panels (0: no bound).
  double max_edge_ratio = 100.0;
  /// A panel's area at least this fraction of its longest edge squared (a
  /// rectangle's width over its length; a sliver below it; 0: no bound).
  double min_aspect = 1e-3;
};

/// One panel's proportions at t*.
struct PanelProportions {
  double longest_edge = 0.0;
  double edge_ratio = 1.0;  ///< longest edge over the design's median longest edge
  double aspect = 1.0;      ///< area over longest edge squared
  int longest = 0;          ///< the longest edge: from corner `longest` to the next
};

/// The area of a planar quad (half the cross product of its diagonals: right for
/// convex and non-convex quads, and for a triangle given with a repeated corner).
double quad_area(const PanelCorners& corners);

/// The proportions of every face of `faces` with corners in `x`.
std::vector<PanelProportions> panel_proportions(const Points& x, const std::vector<Quad>& faces);

/// The bounding-box diagonal of points.
double bounding_diagonal(const Points& x);

/// panel_shapes (panel_nets.h) with the simple panels beyond the bounds marked
/// oversized or slivers.
std::vector<PanelShape> bounded_panel_shapes(const Assembly& assembly, const AssemblyMesh& mesh, const SizeBounds& bounds = {});

/// The model size (bounding-box diagonal at t*) of the panels within the edge
/// bound: what the design's lengths compare with when an oversized panel would
/// make the whole model size meaningless (the model size when none is).
double bounded_model_size(const Design& design, const SizeBounds& bounds = {});

}  // namespace phedra
