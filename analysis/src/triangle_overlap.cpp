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

}  // namespace

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
