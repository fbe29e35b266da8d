#include "phedra/panel_shape.h"

#include <cmath>

namespace phedra {
namespace {

struct Turns {
  std::array<double, 4> turn{};  ///< signed turn at each corner, along the panel's normal
  double corner = 0.0;           ///< largest |corner cross product| (twice a corner triangle's area)
  double edge2 = 0.0;            ///< longest edge, squared
};

Turns turns_of(const PanelCorners& v) {
  std::array<Vec3, 4> crosses;
  Vec3 normal = Vec3::Zero();
  Turns t;
  for (int k = 0; k < 4; ++k) {
    const Vec3 in = v[k] - v[(k + 3) % 4], out = v[(k + 1) % 4] - v[k];
    crosses[k] = in.cross(out);
    if (crosses[k].squaredNorm() > normal.squaredNorm()) normal = crosses[k];
    t.corner = std::max(t.corner, crosses[k].norm());
    t.edge2 = std::max(t.edge2, out.squaredNorm());
  }
  const double n = normal.norm();
  if (n > 0.0) normal /= n;
  for (int k = 0; k < 4; ++k) t.turn[k] = normal.dot(crosses[k]);
  return t;
}

}  // namespace

std::string to_string(PanelShape shape) {
  switch (shape) {
    case PanelShape::convex: return "convex";
    case PanelShape::non_convex: return "non-convex";
    case PanelShape::bow_tie: return "bow-tie";
    case PanelShape::degenerate: return "degenerate";
  }
  return "?";
}

PanelShape panel_shape(const PanelCorners& corners) {
  const Turns t = turns_of(corners);
  if (!(t.corner > 1e-12 * t.edge2)) return PanelShape::degenerate;
  // A straight corner (turn ~ 0) counts with the majority.
  const double straight = 1e-12 * t.edge2;
  int negative = 0;
  for (double turn : t.turn) negative += turn < -straight ? 1 : 0;
  if (negative == 2) return PanelShape::bow_tie;
  return negative == 0 || negative == 4 ? PanelShape::convex : PanelShape::non_convex;
}

std::array<Triangle, 2> panel_triangles(const PanelCorners& v) {
  const Turns t = turns_of(v);
  // The reflex corner is the one whose turn has the minority sign.
  int positive = 0;
  for (double turn : t.turn) positive += turn > 0.0 ? 1 : 0;
  int k = 0;
  if (positive == 1 || positive == 3) {
    const bool minority_positive = positive == 1;
    for (int c = 0; c < 4; ++c) {
      if ((t.turn[c] > 0.0) == minority_positive) k = c;
    }
  }
  return {Triangle{v[k], v[(k + 1) % 4], v[(k + 2) % 4]}, Triangle{v[k], v[(k + 2) % 4], v[(k + 3) % 4]}};
}

}  // namespace phedra
