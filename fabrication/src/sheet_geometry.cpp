#include "phedra/sheet_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace phedra {
namespace {


/// Smallest projection overlap of a and b over the edge normals of `edges`.
double overlap_along_edges(const Polygon2& edges, const Polygon2& a, const Polygon2& b) {
  double least = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const Vec2 e = edges[(k + 1) % edges.size()] - edges[k];
    if (e.squaredNorm() == 0.0) continue;
    const Vec2 axis = Vec2(-e.y(), e.x()).normalized();
    double a0 = std::numeric_limits<double>::infinity(), a1 = -a0, b0 = a0, b1 = -a0;
    for (const Vec2& p : a) a0 = std::min(a0, axis.dot(p)), a1 = std::max(a1, axis.dot(p));
    for (const Vec2& p : b) b0 = std::min(b0, axis.dot(p)), b1 = std::max(b1, axis.dot(p));
    least = std::min(least, std::min(a1, b1) - std::max(a0, b0));
  }
  return least;
}

double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double l2 = ab.squaredNorm();
  const double s = l2 > 0.0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (p - (a + s * ab)).norm();
}

}  // namespace

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

double signed_area2(const Polygon2& polygon) {
  double area = 0.0;
  for (std::size_t k = 0; k < polygon.size(); ++k) area += cross(polygon[k], polygon[(k + 1) % polygon.size()]);
  return area;
}

double convex_overlap(const Polygon2& a, const Polygon2& b) {
  return std::min(overlap_along_edges(a, a, b), overlap_along_edges(b, a, b));
}

std::vector<Polygon2> convex_parts(const Polygon2& polygon) {
  if (polygon.size() != 4) return {polygon};
  const double orientation = signed_area2(polygon) >= 0.0 ? 1.0 : -1.0;
  for (int k = 0; k < 4; ++k) {
    const Vec2 before = polygon[(k + 3) % 4], at = polygon[k], after = polygon[(k + 1) % 4];
    if (orientation * cross(at - before, after - at) < 0.0) {  // reflex corner k: split through it
      return {{polygon[k], polygon[(k + 1) % 4], polygon[(k + 2) % 4]},
              {polygon[k], polygon[(k + 2) % 4], polygon[(k + 3) % 4]}};
    }
  }
  return {polygon};
}

double polygon_overlap(const Polygon2& a, const Polygon2& b) {
  double most = -std::numeric_limits<double>::infinity();
  for (const Polygon2& p : convex_parts(a)) {
    for (const Polygon2& q : convex_parts(b)) most = std::max(most, convex_overlap(p, q));
  }
  return most;
}

bool inside(const Polygon2& polygon, const Vec2& point, double margin) {
  bool in = false;
  for (std::size_t k = 0, j = polygon.size() - 1; k < polygon.size(); j = k++) {
    const Vec2 &a = polygon[k], &b = polygon[j];
    if ((a.y() > point.y()) != (b.y() > point.y()) &&
        point.x() < (b.x() - a.x()) * (point.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      in = !in;
    }
  }
  if (!in || margin <= 0.0) return in;
  for (std::size_t k = 0, j = polygon.size() - 1; k < polygon.size(); j = k++) {
    if (distance_to_segment(point, polygon[k], polygon[j]) < margin) return false;
  }
  return true;
}

Polygon2 Box2::corners() const {
  const Vec2 w = width * axis, h = height * up();
  return {origin, origin + w, origin + w + h, origin + h};
}

bool box_inside(const Polygon2& polygon, const Box2& box, double margin) {
  const Polygon2 c = box.corners();
  for (const Vec2& p : c) {
    if (!inside(polygon, p, margin)) return false;
  }
  for (const Vec2& p : polygon) {
    const Vec2 d = p - box.origin;
    const double s = d.dot(box.axis), t = d.dot(box.up());
    if (s > -margin && s < box.width + margin && t > -margin && t < box.height + margin) return false;
  }
  return true;
}

Polygon2 convex_hull(std::vector<Vec2> points) {
  std::sort(points.begin(), points.end(),
            [](const Vec2& a, const Vec2& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  if (points.size() < 3) return points;
  Polygon2 hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

Box2 minimum_box(const std::vector<Vec2>& points) {
  const Polygon2 hull = convex_hull(points);
  Box2 best;
  double best_area = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < std::max<std::size_t>(hull.size(), 1); ++k) {
    Vec2 axis = hull.size() >= 2 ? Vec2(hull[(k + 1) % hull.size()] - hull[k]) : Vec2::UnitX();
    if (axis.squaredNorm() == 0.0) continue;
    axis.normalize();
    const Vec2 up(-axis.y(), axis.x());
    double s0 = std::numeric_limits<double>::infinity(), s1 = -s0, t0 = s0, t1 = -s0;
    for (const Vec2& p : hull) {
      s0 = std::min(s0, p.dot(axis)), s1 = std::max(s1, p.dot(axis));
      t0 = std::min(t0, p.dot(up)), t1 = std::max(t1, p.dot(up));
    }
    if ((s1 - s0) * (t1 - t0) < best_area) {
      best_area = (s1 - s0) * (t1 - t0);
      best = Box2{s0 * axis + t0 * up, axis, s1 - s0, t1 - t0};
    }
  }
  return best;
}

Vec2 nearest_point(const Box2& box, const Vec2& point) {
  const Vec2 d = point - box.origin;
  const double s = std::clamp(d.dot(box.axis), 0.0, box.width), t = std::clamp(d.dot(box.up()), 0.0, box.height);
  return box.origin + s * box.axis + t * box.up();
}

}  // namespace phedra
