#include "phedra/triangle_overlap.h"

#include <algorithm>
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

double triangle_penetration(const Triangle& p, const Triangle& q) {
  const Vec3 np_raw = (p[1] - p[0]).cross(p[2] - p[0]), nq_raw = (q[1] - q[0]).cross(q[2] - q[0]);
  double scale = 0.0;
  for (int k = 0; k < 3; ++k) {
    scale = std::max({scale, (p[(k + 1) % 3] - p[k]).squaredNorm(), (q[(k + 1) % 3] - q[k]).squaredNorm()});
  }
  const double tiny = 1e-24 * scale * scale;
  if (!(np_raw.squaredNorm() > tiny) || !(nq_raw.squaredNorm() > tiny)) return 0.0;  // no area
  const Vec3 np = np_raw.normalized(), nq = nq_raw.normalized();
  const std::array<double, 3> dq = distances(q, np, p[0]), dp = distances(p, nq, q[0]);
  const double depth = std::min(straddle(dq), straddle(dp));
  if (depth <= 0.0) return depth;
  const Vec3 line = np.cross(nq);
  if (!(line.squaredNorm() > 1e-24)) return 0.0;  // coplanar: contact
  const auto [q0, q1] = section(q, dq, line);
  const auto [p0, p1] = section(p, dp, line);
  const double common = (std::min(p1, q1) - std::max(p0, q0)) / line.norm();
  return std::min(depth, common);
}

}  // namespace phedra
