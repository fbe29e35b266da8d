#include "phedra/linkage.h"

#include "phedra/errors.h"
#include "phedra/tolerances.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace phedra {

const char* to_string(MotionCase c) { return c == MotionCase::a ? "a" : "b"; }

Linkage::Linkage(const Points& column, const CanonicalInput& in) {
  const double s0 = in.heights[0], s1 = in.heights[1];
  const double eps = tolerance::scaled(tolerance::scissor, in.scale);
  bool decided = false;
  for (const Vec3& v : column) {
    const double d0 = (v - Vec3(0, 0, s0)).norm();
    const double d1 = (v - Vec3(0, 0, s1)).norm();
    if (std::abs(d0 - d1) <= eps) continue;  // scissor row: decided by a later row
    if (!decided) {
      case_ = d0 < d1 ? MotionCase::a : MotionCase::b;
      decided = true;
    }
  }
  if (!decided) {
    throw InvalidInputError("", "every trajectory vertex is equidistant from S_0 and S_1: the motion "
                                "parameter is undefined (the trajectory is orthogonal to the axis)");
  }
  const Vec3& v00 = column[0];
  const double moving = case_ == MotionCase::a ? s0 : s1;
  const double other = case_ == MotionCase::a ? s1 : s0;
  moving_radius_ = std::hypot(v00.x(), moving - v00.z());
  other_radius_ = std::hypot(v00.x(), other - v00.z());
  other_sign_ = other < 0.0 ? -1.0 : 1.0;
}

bool Linkage::start(double t, LinkageStart& out, double& margin) const {
  const double r2 = moving_radius_ * moving_radius_;
  const double x2 = r2 - t * t;
  margin = x2 / r2;
  if (!(x2 >= 0.0)) return false;
  const double other2 = std::max(0.0, other_radius_ * other_radius_ - x2);
  const double other = other_sign_ * std::sqrt(other2);
  out.x = std::sqrt(x2);
  if (case_ == MotionCase::a) {
    out.s0 = t;
    out.s1 = other;
  } else {
    out.s1 = t;
    out.s0 = other;
  }
  return true;
}

bool Linkage::rate(double t, const LinkageStart& at, LinkageStart& out) const {
  // x dx/dt = -t; the other apex o keeps x^2 + o^2 = r_other^2: o do/dt = -x dx/dt = t.
  const double other = case_ == MotionCase::a ? at.s1 : at.s0;
  if (!(at.x > 0.0) || other == 0.0) return false;
  out.x = -t / at.x;
  const double d_other = t / other;
  out.s0 = case_ == MotionCase::a ? 1.0 : d_other;
  out.s1 = case_ == MotionCase::a ? d_other : 1.0;
  return std::isfinite(out.x) && std::isfinite(d_other);
}

}  // namespace phedra
