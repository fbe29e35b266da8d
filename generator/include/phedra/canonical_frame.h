#pragma once
// The canonical frame of MATH.md section 1: the axis pi_0 ∩ pi_1 is the z-axis,
// pi_0 is the xz-plane, V_{0,0} lies on the positive x-axis at z = 0. The motion
// keeps this frame fixed, so one rigid map takes every configuration back to
// the user's frame.

#include "phedra/control_polylines.h"
#include "phedra/vector_types.h"

namespace phedra {

class CanonicalFrame {
 public:
  CanonicalFrame() = default;
  /// Requires validate(input) to have passed. Throws InvalidInputError when
  /// V_{0,0} lies on the axis pi_0 ∩ pi_1.
  explicit CanonicalFrame(const ControlPolylines& input);

  Vec3 point_to_canonical(const Vec3& p) const { return rotation_ * (p - origin_); }
  Vec3 vector_to_canonical(const Vec3& v) const { return rotation_ * v; }
  Vec3 point_to_user(const Vec3& p) const { return origin_ + rotation_.transpose() * p; }
  Vec3 vector_to_user(const Vec3& v) const { return rotation_.transpose() * v; }

  /// A user height <X, axis> as a canonical z, and back.
  double height_to_canonical(double h) const { return h - origin_height_; }
  double height_to_user(double z) const { return z + origin_height_; }

  /// Rows: canonical x, y, z axes in user coordinates.
  const Mat3& rotation() const { return rotation_; }
  /// The canonical origin in user coordinates: the point of the apex line at the
  /// height of V_{0,0}.
  const Vec3& origin() const { return origin_; }

 private:
  Mat3 rotation_ = Mat3::Identity();
  Vec3 origin_ = Vec3::Zero();
  double origin_height_ = 0.0;
};

}  // namespace phedra
