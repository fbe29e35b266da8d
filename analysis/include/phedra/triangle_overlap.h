#pragma once
// How deeply two triangles cut into each other. Zero-thickness panels either
// cross (each has points strictly on both sides of the other's plane, along a
// common segment) or merely touch (at a point, along an edge lying on the other,
// or flat on each other when coplanar). The depth of a crossing is the smallest
// of: the length of the common segment, and how far each triangle reaches to
// the less-reached side of the other's plane. It is 0 for every kind of contact
// and negative when the triangles are apart.

#include "phedra/vector_types.h"

#include <array>

namespace phedra {

using Triangle = std::array<Vec3, 3>;

/// The depth above (a length): > 0 crossing, 0 touching (or coplanar, or a
/// triangle without area), < 0 apart.
double triangle_penetration(const Triangle& p, const Triangle& q);

/// A triangle with what every test of it needs, computed once (a panel's
/// triangles are tested against many others in a configuration).
struct PreparedTriangle {
  Triangle corners;
  Vec3 normal = Vec3::Zero();  ///< unit (zero without area)
  double area2 = 0.0;          ///< |cross product|^2
  double edge2 = 0.0;          ///< longest edge, squared
};
PreparedTriangle prepare(const Triangle& t);

/// triangle_penetration(p.corners, q.corners), from the prepared data.
double triangle_penetration(const PreparedTriangle& p, const PreparedTriangle& q);

/// The point of triangle abc nearest to p (Ericson, Real-Time Collision
/// Detection, 5.1.5, by Voronoi regions; a triangle without area: its nearest edge).
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

/// The distance between two triangles (their closest points), 0 when they
/// touch or cross: the least of each corner's distance to the other triangle
/// and each pair of edges' (Ericson, Real-Time Collision Detection, 5.1.5 and
/// 5.1.9). Parts printed in place must keep a clearance: this measures it.
double triangle_distance(const PreparedTriangle& p, const PreparedTriangle& q);

/// triangle_penetration(p, q) > tolerance.
inline bool triangles_penetrate(const Triangle& p, const Triangle& q, double tolerance) {
  return triangle_penetration(p, q) > tolerance;
}

}  // namespace phedra
