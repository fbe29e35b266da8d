#include "phedra/triangle_overlap.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace phedra {
namespace {

/// Signed distances of q's corners from the plane (unit normal n through o).
std::array<double, 3> distances(const Triangle& q, const Vec3& n, const Vec3& o) {
  return {n.dot(q[0] - o), n.dot(q[1] - o), n.dot(q[2] - o)};
}

/// How far q reaches to the less-reached side of the plane (<= 0: one side only).
double straddle(const std::array<double, 3>& d) {
  const double above = std::max({d[0], d[1], d[2]}), below = -std::min({d[0], d[1], d[2]});
  return std::min(above, below);
}

/// The interval, along `direction`, of q's points on the plane (q straddles it).
std::pair<double, double> section(const Triangle& q, const std::array<double, 3>& d, const Vec3& direction) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  auto add = [&](const Vec3& x) {
    const double s = direction.dot(x);
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  };
  for (int k = 0; k < 3; ++k) {
    const int l = (k + 1) % 3;
    if (d[k] == 0.0) add(q[k]);
    if ((d[k] < 0.0 && d[l] > 0.0) || (d[k] > 0.0 && d[l] < 0.0)) add(q[k] + d[k] / (d[k] - d[l]) * (q[l] - q[k]));
  }
  return {lo, hi};
}

/// The squared distance between segments p1q1 and p2q2 (Ericson 5.1.9).
double segments_distance2(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2) {
  const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0.0, t = 0.0;
  if (a <= 0.0 && e <= 0.0) return r.squaredNorm();
  if (a <= 0.0) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= 0.0) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return ((p1 + s * d1) - (p2 + t * d2)).squaredNorm();
}

}  // namespace

Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + d1 / (d1 - d3) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = va + vb + vc;
  if (!(denom > 0.0)) {  // no area: the nearest of its edges
    auto on_segment = [&](const Vec3& u, const Vec3& v) {
      const Vec3 d = v - u;
      const double l = d.squaredNorm();
      return l > 0.0 ? Vec3(u + std::clamp((p - u).dot(d) / l, 0.0, 1.0) * d) : u;
    };
    Vec3 best = on_segment(a, b);
    for (const Vec3& x : {on_segment(b, c), on_segment(c, a)}) {
      if ((x - p).squaredNorm() < (best - p).squaredNorm()) best = x;
    }
    return best;
  }
  return a + (vb / denom) * ab + (vc / denom) * ac;
}

double triangle_distance(const PreparedTriangle& pt, const PreparedTriangle& qt) {
  if (triangle_penetration(pt, qt) > 0.0) return 0.0;  // crossing (touching gives 0 below)
  const Triangle& p = pt.corners;
  const Triangle& q = qt.corners;
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    best = std::min(best, (closest_on_triangle(p[k], q[0], q[1], q[2]) - p[k]).squaredNorm());
    best = std::min(best, (closest_on_triangle(q[k], p[0], p[1], p[2]) - q[k]).squaredNorm());
    for (int l = 0; l < 3; ++l) best = std::min(best, segments_distance2(p[k], p[(k + 1) % 3], q[l], q[(l + 1) % 3]));
  }
  return std::sqrt(best);
}

PreparedTriangle prepare(const Triangle& t) {
  PreparedTriangle p;
  p.corners = t;
  const Vec3 raw = (t[1] - t[0]).cross(t[2] - t[0]);
  p.area2 = raw.squaredNorm();
  p.normal = p.area2 > 0.0 ? Vec3(raw / std::sqrt(p.area2)) : Vec3::Zero();
  for (int k = 0; k < 3; ++k) p.edge2 = std::max(p.edge2, (t[(k + 1) % 3] - t[k]).squaredNorm());
  return p;
}

double triangle_penetration(const Triangle& p, const Triangle& q) { return triangle_penetration(prepare(p), prepare(q)); }

double triangle_penetration(const PreparedTriangle& pt, const PreparedTriangle& qt) {
  const double scale = std::max(pt.edge2, qt.edge2);
  const double tiny = 1e-24 * scale * scale;
  if (!(pt.area2 > tiny) || !(qt.area2 > tiny)) return 0.0;  // no area
  const Triangle& p = pt.corners;
  const Triangle& q = qt.corners;
  const Vec3& np = pt.normal;
  const Vec3& nq = qt.normal;
  const std::array<double, 3> dq = distances(q, np, p[0]);
  const double above_q = straddle(dq);
  if (above_q <= 0.0) return above_q;
  const std::array<double, 3> dp = distances(p, nq, q[0]);
  const double depth = std::min(above_q, straddle(dp));
  if (depth <= 0.0) return depth;
  const Vec3 line = np.cross(nq);
  if (!(line.squaredNorm() > 1e-24)) return 0.0;  // coplanar: contact
  const auto [q0, q1] = section(q, dq, line);
  const auto [p0, p1] = section(p, dp, line);
  const double common = (std::min(p1, q1) - std::max(p0, q0)) / line.norm();
  return std::min(depth, common);
}

}  // namespace phedra
