#include "phedra/panel_shape.h"

#include <algorithm>
#include <cmath>

namespace phedra {

std::string to_string(PanelShape shape) {
  switch (shape) {
    case PanelShape::convex: return "convex";
    case PanelShape::non_convex: return "non-convex";
    case PanelShape::bow_tie: return "bow-tie";
    case PanelShape::degenerate: return "degenerate";
    case PanelShape::oversized: return "oversized";
    case PanelShape::sliver: return "sliver";
  }
  return "?";
}

std::array<double, 4> corner_turns(const PanelCorners& v, const Vec3& normal) {
  std::array<double, 4> t{};
  for (int k = 0; k < 4; ++k) {
    const Vec3 in = v[k] - v[(k + 3) % 4], out = v[(k + 1) % 4] - v[k];
    t[k] = normal.dot(in.cross(out));
  }
  return t;
}

Vec3 quad_normal(const PanelCorners& v) {
  Vec3 best = Vec3::Zero();
  for (int k = 0; k < 4; ++k) {
    const Vec3 cross = (v[k] - v[(k + 3) % 4]).cross(v[(k + 1) % 4] - v[k]);
    if (cross.squaredNorm() > best.squaredNorm()) best = cross;
  }
  const double norm = best.norm();
  return norm > 0.0 ? Vec3(best / norm) : Vec3::Zero();
}

PanelShape shape_from_turns(const std::array<double, 4>& turns, double straight, double flat) {
  if (!(std::max({std::abs(turns[0]), std::abs(turns[1]), std::abs(turns[2]), std::abs(turns[3])}) > flat)) {
    return PanelShape::degenerate;
  }
  int negative = 0;
  for (double t : turns) negative += t < -straight ? 1 : 0;
  if (negative == 2) return PanelShape::bow_tie;
  return negative == 0 || negative == 4 ? PanelShape::convex : PanelShape::non_convex;
}

double longest_edge_squared(const PanelCorners& v) {
  double e2 = 0.0;
  for (int k = 0; k < 4; ++k) e2 = std::max(e2, (v[(k + 1) % 4] - v[k]).squaredNorm());
  return e2;
}

PanelShape panel_shape(const PanelCorners& corners) {
  // A straight corner (turn within 1e-12 of the longest edge squared) counts as positive.
  const double straight = 1e-12 * longest_edge_squared(corners);
  return shape_from_turns(corner_turns(corners, quad_normal(corners)), straight, straight);
}

std::array<Triangle, 2> panel_triangles(const PanelCorners& v) {
  const std::array<double, 4> turn = corner_turns(v, quad_normal(v));
  // The reflex corner is the one whose turn has the minority sign.
  int positive = 0;
  for (double t : turn) positive += t > 0.0 ? 1 : 0;
  int k = 0;
  if (positive == 1 || positive == 3) {
    const bool minority_positive = positive == 1;
    for (int c = 0; c < 4; ++c) {
      if ((turn[c] > 0.0) == minority_positive) k = c;
    }
  }
  return {Triangle{v[k], v[(k + 1) % 4], v[(k + 2) % 4]}, Triangle{v[k], v[(k + 2) % 4], v[(k + 3) % 4]}};
}

}  // namespace phedra
