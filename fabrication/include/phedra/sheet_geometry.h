#pragma once
// Plane geometry of printed sheets: polygons that must not overlap, labels
// (rotated boxes) that must fit inside their panel, and the smallest box around
// a piece. Shared by the cut-sheet layout and its tests.

#include "phedra/vector_types.h"

#include <array>
#include <vector>

namespace phedra {

using Polygon2 = std::vector<Vec2>;

/// How deeply two convex polygons overlap: the smallest overlap of their
/// projections over every edge normal (separating axis test). > 0 overlapping
/// interiors, 0 touching, < 0 apart.
double convex_overlap(const Polygon2& a, const Polygon2& b);

/// The polygon split into convex pieces: itself when convex (or a triangle),
/// else its two triangles split along the diagonal that lies inside it.
std::vector<Polygon2> convex_parts(const Polygon2& polygon);

/// convex_overlap over the convex parts of two simple polygons (max over pairs).
double polygon_overlap(const Polygon2& a, const Polygon2& b);

/// The z of the cross product of two plane vectors (> 0: b is counter-clockwise from a).
double cross(const Vec2& a, const Vec2& b);

/// Twice the signed area (> 0 counter-clockwise).
double signed_area2(const Polygon2& polygon);

/// Point in a simple polygon, `margin` inside it (distance to every edge >= margin).
bool inside(const Polygon2& polygon, const Vec2& point, double margin = 0.0);

/// A rotated box: origin, unit axis (its bottom edge's direction), size along
/// the axis (width) and across it (height, to the left of the axis).
struct Box2 {
  Vec2 origin = Vec2::Zero();
  Vec2 axis = Vec2::UnitX();
  double width = 0.0, height = 0.0;
  Vec2 up() const { return Vec2(-axis.y(), axis.x()); }
  Polygon2 corners() const;
};

/// The point of the box nearest to `point` (where a leader from there ends).
Vec2 nearest_point(const Box2& box, const Vec2& point);

/// The box lies inside the polygon (its corners inside, no polygon corner inside it), with `margin`.
bool box_inside(const Polygon2& polygon, const Box2& box, double margin = 0.0);

/// The smallest-area box around the points (one side along an edge of their convex hull).
Box2 minimum_box(const std::vector<Vec2>& points);

/// Convex hull, counter-clockwise.
Polygon2 convex_hull(std::vector<Vec2> points);

}  // namespace phedra
