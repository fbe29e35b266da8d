#include "phedra/strip_chain.h"

#include "phedra/errors.h"
#include "phedra/tolerances.h"

#include <cmath>
#include <string>

namespace phedra {

StripChain::StripChain(const Points& column, double s0, double s1) {
  const std::size_t m = column.size() - 1;
  r0_squared_.resize(m);
  r1_squared_.resize(m);
  rp_squared_.resize(m);
  branch_.resize(m);
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
  }
}

bool StripChain::advance(std::size_t i, double s0, double s1, const Vec3& p, Vec3& out, double& margin,
                         bool clamp) const {
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
  const double sine = branch_[k] * std::sqrt(margin);
  const double cosine = c > 1.0 ? 1.0 : (c < -1.0 ? -1.0 : c);
  const double ux = p.x() / rho, uy = p.y() / rho;
  out = Vec3(radius * (cosine * ux - sine * uy), radius * (cosine * uy + sine * ux), h);
  return radius2 > 0.0 && rho2 > 0.0;
}

StripMargin StripChain::trace(double s0, double s1, const Vec3& first) const {
  StripMargin worst;
  Vec3 previous = first;
  Vec3 next;
  for (std::size_t i = 1; i <= strips(); ++i) {
    double margin;
    if (!advance(i, s0, s1, previous, next, margin)) return {-1.0, i};
    if (margin < worst.value) worst = {margin, i};
    previous = next;
  }
  return worst;
}

}  // namespace phedra
