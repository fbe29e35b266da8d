#include "phedra/geometry_checks.h"

#include <cmath>

namespace phedra {

Deviation planarity(const std::vector<Quad>& faces, std::span<const Vec3> v) {
  Deviation worst;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const Quad& q = faces[f];
    // The triangle without corner k, and the distance of corner k from its plane.
    double best_area = -1.0, distance = 0.0;
    for (int k = 0; k < 4; ++k) {
      const Vec3& a = v[q[(k + 1) % 4]];
      const Vec3& b = v[q[(k + 2) % 4]];
      const Vec3& c = v[q[(k + 3) % 4]];
      const Vec3 normal = (b - a).cross(c - a);
      const double area = normal.norm();
      if (area > best_area) {
        best_area = area;
        distance = area > 0.0 ? std::abs(normal.dot(v[q[k]] - a)) / area : 0.0;
      }
    }
    if (!(distance <= worst.value)) worst = {distance, f};
  }
  return worst;
}

std::vector<double> segment_lengths(const std::vector<Segment>& segments, std::span<const Vec3> v) {
  std::vector<double> lengths;
  lengths.reserve(segments.size());
  for (const Segment& s : segments) lengths.push_back((v[s[1]] - v[s[0]]).norm());
  return lengths;
}

Deviation length_deviation(const std::vector<Segment>& segments, std::span<const double> reference,
                           std::span<const Vec3> v) {
  Deviation worst;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const double d = std::abs((v[segments[k][1]] - v[segments[k][0]]).norm() - reference[k]);
    if (!(d <= worst.value)) worst = {d, k};
  }
  return worst;
}

double bounding_box_diagonal(std::span<const Vec3> points) {
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return points.empty() ? 0.0 : (hi - lo).norm();
}

}  // namespace phedra
