#include "phedra/strip_chain.h"

#include "phedra/errors.h"
#include "phedra/tolerances.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace phedra {

StripChain::StripChain(const Points& column, double s0, double s1) {
  const std::size_t m = column.size() - 1;
  r0_squared_.resize(m);
  r1_squared_.resize(m);
  rp_squared_.resize(m);
  branch_.resize(m);
  half_difference_.resize(m);
  const Vec3 apex0(0, 0, s0), apex1(0, 0, s1);
  for (std::size_t i = 1; i <= m; ++i) {
    const Vec3& x = column[i];
    const Vec3& p = column[i - 1];
    r0_squared_[i - 1] = (x - apex0).squaredNorm();
    r1_squared_[i - 1] = (x - apex1).squaredNorm();
    rp_squared_[i - 1] = (x - p).squaredNorm();
    const double turn = p.x() * x.y() - p.y() * x.x();  // sign of det(X-S0, X-S1, X-P)
    const double sine = turn / (p.head<2>().norm() * x.head<2>().norm());
    if (std::abs(sine) <= tolerance::parallel_sine) {
      throw InvalidInputError("directions[" + std::to_string(i) + "]",
                              "the axial profile planes " + std::to_string(i - 1) + " and " + std::to_string(i) +
                                  " coincide: the input is in a bifurcation configuration (a flexion limit)");
    }
    branch_[i - 1] = turn > 0.0 ? 1.0 : -1.0;
    half_difference_[i - 1] = 0.5 * (r1_squared_[i - 1] - r0_squared_[i - 1]);
  }
}

bool StripChain::advance(std::size_t i, double s0, double s1, const Vec3& p, Vec3& out, double& margin,
                         bool clamp, bool flipped) const {
  const std::size_t k = i - 1;
  const double r0 = r0_squared_[k], r1 = r1_squared_[k];
  // Height where the spheres about S_0 and S_1 meet, and the circle's radius.
  const double h = 0.5 * (s0 + s1) + 0.5 * (r1 - r0) / (s0 - s1);
  double radius2 = r0 - (h - s0) * (h - s0);
  const double rho2 = p.x() * p.x() + p.y() * p.y();
  const double dz = h - p.z();
  if (clamp && radius2 < 0.0 && radius2 > -clamp_margin * r0) radius2 = 0.0;
  const double radius = std::sqrt(radius2);
  const double rho = std::sqrt(rho2);
  const double c = (radius2 + rho2 + dz * dz - rp_squared_[k]) / (2.0 * radius * rho);
  margin = 1.0 - c * c;
  if (!(margin >= 0.0)) {
    if (!clamp || !(margin >= -clamp_margin)) return false;
    margin = 0.0;
  }
  const double sine = (flipped ? -branch_[k] : branch_[k]) * std::sqrt(margin);
  const double cosine = c > 1.0 ? 1.0 : (c < -1.0 ? -1.0 : c);
  const double ux = p.x() / rho, uy = p.y() / rho;
  out = Vec3(radius * (cosine * ux - sine * uy), radius * (cosine * uy + sine * ux), h);
  return radius2 > 0.0 && rho2 > 0.0;
}

bool StripChain::rate(double s0, double s1, const Vec3& p, const Vec3& x, double ds0, double ds1,
                      const Vec3& dp, Vec3& out) const {
  // |X - S_0|, |X - S_1|, |X - P| constant: (X - S_0) . (dX - dS_0) = 0 and so on.
  const Vec3 a = x - Vec3(0, 0, s0), b = x - Vec3(0, 0, s1), c = x - p;
  const double ra = a.z() * ds0, rb = b.z() * ds1, rc = c.dot(dp);
  const Vec3 bc = b.cross(c), ca = c.cross(a), ab = a.cross(b);
  const double det = a.dot(bc);
  if (det == 0.0) return false;
  out = (ra * bc + rb * ca + rc * ab) / det;
  return out.allFinite();
}

double StripChain::strip_value(std::size_t k, double h, double r2, double previous_h, double previous_r2) const {
  // c = (r2 + r2_prev + dz^2 - rp^2) / (2 r r_prev) as in advance(), and
  // 1 - c^2 = (4 r2 r2_prev - num^2) / (4 r2 r2_prev) without a square root.
  if (!(r2 > 0.0 && previous_r2 > 0.0)) return std::min(r2 / r0_squared_[k], -std::numeric_limits<double>::min());
  const double dz = h - previous_h;
  const double numerator = r2 + previous_r2 + dz * dz - rp_squared_[k];
  const double denominator = 4.0 * r2 * previous_r2;
  return (denominator - numerator * numerator) / denominator;
}

StripMargin StripChain::margin(double s0, double s1, double x) const {
  StripMargin worst;
  const double middle = 0.5 * (s0 + s1), inverse = 1.0 / (s0 - s1);
  double previous_h = 0.0, previous_r2 = x * x;
  const std::size_t m = strips();
  for (std::size_t k = 0; k < m; ++k) {
    double h, r2;
    circle(k, s0, middle, inverse, h, r2);
    const double value = strip_value(k, h, r2, previous_h, previous_r2);
    if (!(value >= worst.value)) worst = {value, k + 1};
    previous_h = h;
    previous_r2 = r2;
  }
  return worst;
}

double StripChain::strip_margin(std::size_t i, double s0, double s1, double x) const {
  const double middle = 0.5 * (s0 + s1), inverse = 1.0 / (s0 - s1);
  double previous_h = 0.0, previous_r2 = x * x, h, r2;
  if (i >= 2) circle(i - 2, s0, middle, inverse, previous_h, previous_r2);
  circle(i - 1, s0, middle, inverse, h, r2);
  return strip_value(i - 1, h, r2, previous_h, previous_r2);
}

}  // namespace phedra
