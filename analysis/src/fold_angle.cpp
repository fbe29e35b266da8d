#include "phedra/fold_angle.h"

#include <cmath>
#include <numbers>

namespace phedra {

double fold_angle_degrees(const Vec3& nf, const Vec3& ng, const Vec3& a, const Vec3& b) {
  const Vec3 edge = (b - a).normalized();
  return std::atan2(-nf.cross(ng).dot(edge), nf.dot(ng)) * 180.0 / std::numbers::pi;
}

}  // namespace phedra
