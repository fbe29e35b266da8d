#include "phedra/solid_crossing.h"

#include "phedra/triangle_overlap.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace phedra {
namespace {

Box box_of_points(const Vec3& a, const Vec3& b, const Vec3& c) {
  return Box{a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c)};
}

struct Near {
  PreparedTriangle triangle;
  Box box;  ///< in the first solid's frame
};

}  // namespace

OrientedSolid orient(const Solid& solid) {
  OrientedSolid o;
  o.solid = &solid;
  const std::vector<Vec3>& v = solid.vertices;
  o.box = Box{v.front(), v.front()};
  for (const Vec3& p : v) o.box.lo = o.box.lo.cwiseMin(p), o.box.hi = o.box.hi.cwiseMax(p);
  // z along the longest edge, x along the largest triangle's normal (made
  // perpendicular to z), y completing the frame. Any frame bounds the solid;
  // these make a prism's box tight.
  Vec3 z = Vec3::UnitZ(), x = Vec3::Zero();
  double longest = 0.0, largest = 0.0;
  for (const auto& t : solid.triangles) {
    for (int k = 0; k < 3; ++k) {
      const Vec3 e = v[t[(k + 1) % 3]] - v[t[k]];
      if (e.squaredNorm() > longest) longest = e.squaredNorm(), z = e;
    }
    const Vec3 n = (v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]);
    if (n.squaredNorm() > largest) largest = n.squaredNorm(), x = n;
  }
  z.normalize();
  x -= x.dot(z) * z;
  if (!(x.squaredNorm() > 1e-12 * largest) || !(largest > 0.0)) {  // no face off the longest edge's line: any perpendicular
    x = std::abs(z.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    x -= x.dot(z) * z;
  }
  x.normalize();
  const Vec3 y = z.cross(x);
  o.axes.row(0) = x;
  o.axes.row(1) = y;
  o.axes.row(2) = z;
  const Vec3 first = o.axes * v.front();
  o.local = Box{first, first};
  for (const Vec3& p : v) {
    const Vec3 q = o.axes * p;
    o.local.lo = o.local.lo.cwiseMin(q), o.local.hi = o.local.hi.cwiseMax(q);
  }
  return o;
}

namespace {

Box grown(const Box& b, double by) { return Box{(b.lo.array() - by).matrix(), (b.hi.array() + by).matrix()}; }

/// The triangles of a and b that may be within `by` of the other: each in the
/// other's oriented box grown by it, boxed in a's frame (grown by it).
void near_pairs(const OrientedSolid& a, const OrientedSolid& b, double by, std::vector<Near>& near_a, std::vector<Near>& near_b) {
  const Solid& sa = *a.solid;
  const Solid& sb = *b.solid;
  const Box a_local = grown(a.local, by), b_local = grown(b.local, by);
  for (const auto& t : sb.triangles) {
    const Triangle tri{sb.vertices[t[0]], sb.vertices[t[1]], sb.vertices[t[2]]};
    const Box in_a = box_of_points(a.axes * tri[0], a.axes * tri[1], a.axes * tri[2]);
    if (in_a.overlaps(a_local)) near_b.push_back({prepare(tri), grown(in_a, by)});
  }
  if (near_b.empty()) return;
  for (const auto& t : sa.triangles) {
    const Triangle tri{sa.vertices[t[0]], sa.vertices[t[1]], sa.vertices[t[2]]};
    if (!box_of_points(b.axes * tri[0], b.axes * tri[1], b.axes * tri[2]).overlaps(b_local)) continue;
    near_a.push_back({prepare(tri), box_of_points(a.axes * tri[0], a.axes * tri[1], a.axes * tri[2])});
  }
}

}  // namespace

double solids_gap(const OrientedSolid& a, const OrientedSolid& b, double within) {
  if (!grown(a.box, within).overlaps(b.box)) return within;
  std::vector<Near> near_a, near_b;
  near_pairs(a, b, within, near_a, near_b);
  double gap = within;
  for (const Near& p : near_a) {
    for (const Near& q : near_b) {
      if (!p.box.overlaps(q.box)) continue;
      gap = std::min(gap, triangle_distance(p.triangle, q.triangle));
      if (gap <= 0.0) return 0.0;
    }
  }
  return gap;
}

double solids_penetration(const OrientedSolid& a, const OrientedSolid& b, double enough) {
  if (!a.box.overlaps(b.box)) return 0.0;
  std::vector<Near> near_a, near_b;
  near_pairs(a, b, 0.0, near_a, near_b);
  double deepest = 0.0;
  for (const Near& p : near_a) {
    for (const Near& q : near_b) {
      if (!p.box.overlaps(q.box)) continue;
      deepest = std::max(deepest, triangle_penetration(p.triangle, q.triangle));
      if (deepest > enough) return deepest;
    }
  }
  return deepest;
}

}  // namespace phedra
