#include "phedra/validation.h"

#include "phedra/errors.h"
#include "phedra/number_format.h"
#include "phedra/tolerances.h"

#include <cmath>
#include <string>

namespace phedra {
namespace {

std::string indexed(const char* field, std::size_t i) { return std::string(field) + "[" + std::to_string(i) + "]"; }

void check_counts(const ControlPolylines& in) {
  if (in.trajectory.size() < 2) {
    throw InvalidInputError("trajectory", "needs at least 2 points (2 profiles), got " +
                                              std::to_string(in.trajectory.size()));
  }
  if (in.directions.size() != in.trajectory.size()) {
    throw InvalidInputError("directions", "expected " + std::to_string(in.trajectory.size()) +
                                              " vectors (one per trajectory point), got " +
                                              std::to_string(in.directions.size()));
  }
  if (in.apex_heights.size() < 3) {
    throw InvalidInputError("apex_heights", "needs at least 3 apexes S_0, S_1, S_2, got " +
                                                std::to_string(in.apex_heights.size()));
  }
  const std::size_t expected_signs = in.apex_heights.size() - 2;
  if (in.signs.size() != expected_signs) {
    throw InvalidInputError("signs", "expected " + std::to_string(expected_signs) +
                                         " signs (one per inner apex S_1..S_" + std::to_string(expected_signs) +
                                         "), got " + std::to_string(in.signs.size()));
  }
}

void check_finite(const Vec3& v, const std::string& field) {
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(v[k])) throw InvalidInputError(field + "[" + std::to_string(k) + "]", "is not a finite number");
  }
}

void check_all_finite(const ControlPolylines& in) {
  for (std::size_t i = 0; i < in.trajectory.size(); ++i) check_finite(in.trajectory[i], indexed("trajectory", i));
  for (std::size_t i = 0; i < in.directions.size(); ++i) check_finite(in.directions[i], indexed("directions", i));
  check_finite(in.axis, "axis");
  for (std::size_t j = 0; j < in.apex_heights.size(); ++j) {
    if (!std::isfinite(in.apex_heights[j])) throw InvalidInputError(indexed("apex_heights", j), "is not a finite number");
  }
}

void check_axis(const Vec3& axis) {
  const double length = axis.norm();
  if (length == 0.0) throw InvalidInputError("axis", "is the zero vector; it must be a unit vector");
  if (std::abs(length - 1.0) > tolerance::axis_unit) {
    throw InvalidInputError("axis", "must be a unit vector, its length is " + format_number(length));
  }
}

void check_directions(const ControlPolylines& in) {
  for (std::size_t i = 0; i < in.directions.size(); ++i) {
    const Vec3& d = in.directions[i];
    const double length = d.norm();
    if (length == 0.0) throw InvalidInputError(indexed("directions", i), "is the zero vector (D_i = V_{i,0})");
    const double along_axis = d.dot(in.axis);
    if (std::abs(along_axis) > tolerance::orthogonality * length) {
      throw InvalidInputError(indexed("directions", i),
                              "is not orthogonal to the axis: <d, axis> = " + format_number(along_axis) +
                                  " for |d| = " + format_number(length));
    }
  }
}

void check_trajectory(const ControlPolylines& in, double scale) {
  const double eps = tolerance::scaled(tolerance::coincident, scale);
  for (std::size_t i = 1; i < in.trajectory.size(); ++i) {
    if ((in.trajectory[i] - in.trajectory[i - 1]).norm() <= eps) {
      throw InvalidInputError(indexed("trajectory", i), "coincides with trajectory[" + std::to_string(i - 1) +
                                                            "] (consecutive points must differ)");
    }
  }
  const double h0 = in.trajectory[0].dot(in.axis);
  bool orthogonal = true;
  for (const Vec3& p : in.trajectory) orthogonal = orthogonal && std::abs(p.dot(in.axis) - h0) <= eps;
  if (orthogonal) {
    throw InvalidInputError("trajectory", "lies in a plane orthogonal to the axis: this is a T-hedron, "
                                          "not a P-hedron (the paper excludes it)");
  }
}

void check_apexes(const ControlPolylines& in, double scale) {
  const double eps = tolerance::scaled(tolerance::coincident, scale);
  const auto& z = in.apex_heights;
  for (std::size_t j = 0; j + 1 < z.size(); ++j) {
    for (std::size_t k = j + 1; k < z.size() && k <= j + 2; ++k) {
      if (std::abs(z[j] - z[k]) <= eps) {
        throw InvalidInputError(indexed("apex_heights", k),
                                "equals apex_heights[" + std::to_string(j) + "] = " + format_number(z[j]) +
                                    ": three consecutive apexes must be pairwise distinct");
      }
    }
  }
}

/// Consecutive profile planes pi_i, pi_{i+1}: neither parallel nor identical.
void check_profile_planes(const ControlPolylines& in, double scale) {
  const Vec3& a = in.axis;
  for (std::size_t i = 0; i + 1 < in.directions.size(); ++i) {
    const Vec3 d0 = in.directions[i].normalized();
    const Vec3 d1 = in.directions[i + 1].normalized();
    const double sine = a.dot(d0.cross(d1));
    if (std::abs(sine) > tolerance::parallel_sine) continue;
    const Vec3 offset = in.trajectory[i + 1] - in.trajectory[i];
    const Vec3 normal = a.cross(d0);
    const std::string planes = "profile planes " + std::to_string(i) + " and " + std::to_string(i + 1);
    if (std::abs(offset.dot(normal)) <= tolerance::scaled(tolerance::coincident, scale)) {
      throw InvalidInputError(indexed("directions", i + 1),
                              planes + " are identical: the input is in a bifurcation configuration "
                                       "(a flexion limit, paper footnote 1); rotate directions[" +
                                  std::to_string(i + 1) + "] about the axis");
    }
    throw InvalidInputError(indexed("directions", i + 1),
                            planes + " are parallel: a translational strip, which the P-hedron "
                                     "construction does not cover (paper footnote 2)");
  }
}

}  // namespace

double input_scale(const ControlPolylines& in) {
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const Vec3& p : in.trajectory) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  double zlo = INFINITY, zhi = -INFINITY;
  for (double z : in.apex_heights) {
    zlo = std::min(zlo, z);
    zhi = std::max(zhi, z);
  }
  double scale = 0.0;
  if (!in.trajectory.empty()) scale += (hi - lo).norm();
  if (!in.apex_heights.empty()) scale += zhi - zlo;
  return scale;
}

void validate(const ControlPolylines& in) {
  check_counts(in);
  check_all_finite(in);
  check_axis(in.axis);
  check_directions(in);
  const double scale = input_scale(in);
  check_trajectory(in, scale);
  check_apexes(in, scale);
  check_profile_planes(in, scale);
}

}  // namespace phedra
