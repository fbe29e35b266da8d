#include "phedra/canonical_frame.h"

#include "phedra/errors.h"
#include "phedra/number_format.h"
#include "phedra/tolerances.h"
#include "phedra/validation.h"

namespace phedra {

CanonicalFrame::CanonicalFrame(const ControlPolylines& in) {
  const Vec3 a = in.axis.normalized();
  // The apex line pi_0 ∩ pi_1 has direction a; find its point O with <O, a> = 0
  // as the intersection of the two profile lines in the plane orthogonal to a.
  const Vec3 u = a.unitOrthogonal();
  const Vec3 v = a.cross(u);
  auto flat = [&](const Vec3& p) { return Vec2(u.dot(p), v.dot(p)); };
  const Vec2 p0 = flat(in.trajectory[0]), p1 = flat(in.trajectory[1]);
  const Vec2 d0 = flat(in.directions[0]), d1 = flat(in.directions[1]);
  auto cross = [](const Vec2& x, const Vec2& y) { return x.x() * y.y() - x.y() * y.x(); };
  const double s = cross(p1 - p0, d1) / cross(d0, d1);  // validate() excluded parallel planes
  const Vec2 axis_point = p0 + s * d0;
  const Vec3 offset = in.trajectory[0] - (axis_point.x() * u + axis_point.y() * v);
  const Vec3 radial = offset - offset.dot(a) * a;
  const double distance = radial.norm();
  if (distance <= tolerance::scaled(tolerance::coincident, input_scale(in))) {
    throw InvalidInputError("trajectory[0]", "V_{0,0} lies on the apex line pi_0 ∩ pi_1 (distance " +
                                                 format_number(distance) + "); move it off the axis");
  }
  const Vec3 ex = radial / distance;
  const Vec3 ey = a.cross(ex);
  rotation_.row(0) = ex.transpose();
  rotation_.row(1) = ey.transpose();
  rotation_.row(2) = a.transpose();
  origin_height_ = in.trajectory[0].dot(a);
  origin_ = axis_point.x() * u + axis_point.y() * v + origin_height_ * a;
}

}  // namespace phedra
