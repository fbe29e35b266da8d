#include "phedra/geometry_checks.h"

#include <algorithm>
#include <cmath>

namespace phedra {

Deviation planarity(const std::vector<Quad>& faces, std::span<const Vec3> v) {
  Deviation worst;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const Quad& q = faces[f];
    const Vec3 &p0 = v[q[0]], &p1 = v[q[1]], &p2 = v[q[2]], &p3 = v[q[3]];
    // The distance of corner k from the plane of the other three is |det| / |n_k|
    // (det: six times the signed volume of the tetrahedron, the same for every k;
    // n_k: the normal of the triangle without k). The best-conditioned triangle is
    // the largest, so one square root and one division a face.
    const Vec3 e1 = p1 - p0, e2 = p2 - p0, e3 = p3 - p0;
    const Vec3 n3 = e1.cross(e2);  // triangle 0 1 2 (without 3)
    const Vec3 n1 = e2.cross(e3);  // 0 2 3
    const Vec3 n2 = e1.cross(e3);  // 0 1 3
    const Vec3 n0 = (p2 - p1).cross(p3 - p1);  // 1 2 3
    const double det = n3.dot(e3);
    const double area2 = std::max(std::max(n0.squaredNorm(), n1.squaredNorm()), std::max(n2.squaredNorm(), n3.squaredNorm()));
    const double distance = area2 > 0.0 ? std::abs(det) / std::sqrt(area2) : 0.0;
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
