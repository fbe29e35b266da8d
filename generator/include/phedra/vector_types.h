#pragma once
// Vector types used throughout phedra (Eigen, double precision).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

namespace phedra {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

/// A list of 3D points; Vec3 is not a vectorisable fixed-size type, so
/// std::vector needs no aligned allocator.
using Points = std::vector<Vec3>;

}  // namespace phedra
