#include "phedra/smooth_trajectory.h"

#include "phedra/errors.h"
#include "phedra/number_format.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace phedra {
namespace {

/// Two unit vectors that make (e1, e2, axis) right-handed and orthonormal.
std::pair<Vec3, Vec3> plane_basis(const Vec3& axis) {
  Vec3 e1 = Vec3::UnitX() - axis.x() * axis;
  if (e1.norm() < 0.5) e1 = Vec3::UnitY() - axis.y() * axis;
  e1.normalize();
  return {e1, axis.cross(e1)};
}

}  // namespace

SmoothCurve helix_curve(const HelixSpec& spec, const Vec3& axis_in) {
  const std::string field = "trajectory.helix";
  const Vec3 axis = axis_in.normalized();
  const Vec3 center = spec.center;
  const double radius = spec.radius, rise = spec.rise_per_turn, turns = spec.turns, start = spec.start_angle_degrees;
  const bool clockwise = spec.clockwise;
  if (!(radius > 0.0)) throw InvalidInputError(field + ".radius", "must be positive, got " + format_number(radius));
  if (!(turns > 0.0)) throw InvalidInputError(field + ".turns", "must be positive, got " + format_number(turns));
  if (turns > 1000.0) throw InvalidInputError(field + ".turns", "at most 1000 turns, got " + format_number(turns));
  const std::pair<Vec3, Vec3> basis = plane_basis(axis);
  const Vec3 e1 = basis.first, e2 = basis.second;  // (lambdas cannot capture structured bindings in C++17 clang)
  const double theta0 = start * std::numbers::pi / 180.0;
  const double span = (clockwise ? -1.0 : 1.0) * 2.0 * std::numbers::pi * turns;
  const double climb = rise * turns;  // along the axis over the whole curve
  SmoothCurve c;
  c.kind = "helix";
  c.point = [=](double u) {
    const double q = theta0 + span * u;
    return Vec3(center + radius * (std::cos(q) * e1 + std::sin(q) * e2) + climb * u * axis);
  };
  c.tangent = [=](double u) {
    const double q = theta0 + span * u;
    return Vec3(radius * span * (-std::sin(q) * e1 + std::cos(q) * e2) + climb * axis);
  };
  return c;
}

/// Clamped uniform B-spline: knots 0 (degree + 1 times), 1/(k), ..., 1 (degree + 1 times).
SmoothCurve spline_curve(const Points& control, int degree) {
  const std::string field = "trajectory.spline";
  if (degree < 1 || degree > 7) {
    throw InvalidInputError(field + ".degree", "expected a whole number from 1 to 7, got " + std::to_string(degree));
  }
  if (control.size() < static_cast<std::size_t>(degree) + 1) {
    throw InvalidInputError(field + ".control_points", "a degree-" + std::to_string(degree) + " spline needs at least " +
                                                           std::to_string(degree + 1) + " control points, got " +
                                                           std::to_string(control.size()));
  }
  const std::size_t n = control.size();
  std::vector<double> knots;
  const std::size_t spans = n - static_cast<std::size_t>(degree);
  for (int k = 0; k < degree; ++k) knots.push_back(0.0);
  for (std::size_t k = 0; k <= spans; ++k) knots.push_back(static_cast<double>(k) / static_cast<double>(spans));
  for (int k = 0; k < degree; ++k) knots.push_back(1.0);
  // de Boor's algorithm on control points `p` with knots `t` and degree `p_deg`.
  auto evaluate = [](const Points& p, const std::vector<double>& t, int p_deg, double u) {
    const std::size_t count = p.size();
    std::size_t k = static_cast<std::size_t>(p_deg);
    while (k + 1 < count && u >= t[k + 1]) ++k;
    std::vector<Vec3> d(static_cast<std::size_t>(p_deg) + 1);
    for (int j = 0; j <= p_deg; ++j) d[j] = p[k - static_cast<std::size_t>(p_deg) + static_cast<std::size_t>(j)];
    for (int r = 1; r <= p_deg; ++r) {
      for (int j = p_deg; j >= r; --j) {
        const std::size_t i = k - static_cast<std::size_t>(p_deg) + static_cast<std::size_t>(j);
        const double denominator = t[i + static_cast<std::size_t>(p_deg) + 1 - static_cast<std::size_t>(r)] - t[i];
        const double alpha = denominator > 0.0 ? (u - t[i]) / denominator : 0.0;
        d[j] = (1.0 - alpha) * d[j - 1] + alpha * d[j];
      }
    }
    return d[static_cast<std::size_t>(p_deg)];
  };
  // The derivative is a degree - 1 spline on the differences of the control points.
  Points differences;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    differences.push_back(degree * (control[i + 1] - control[i]) / (knots[i + static_cast<std::size_t>(degree) + 1] - knots[i + 1]));
  }
  const std::vector<double> inner(knots.begin() + 1, knots.end() - 1);
  SmoothCurve c;
  c.kind = "B-spline of degree " + std::to_string(degree);
  c.point = [=](double u) { return evaluate(control, knots, degree, std::clamp(u, 0.0, 1.0)); };
  c.tangent = [=](double u) {
    if (degree == 1) {
      return evaluate(differences, inner, 0, std::clamp(u, 0.0, 1.0 - 1e-15));
    }
    return evaluate(differences, inner, degree - 1, std::clamp(u, 0.0, 1.0));
  };
  return c;
}

namespace {

/// Largest distance of the curve between u0 and u1 from the chord (32 points).
double chord_deviation(const SmoothCurve& curve, double u0, double u1) {
  const Vec3 a = curve.point(u0), b = curve.point(u1), ab = b - a;
  const double length2 = ab.squaredNorm();
  double worst = 0.0;
  for (int k = 1; k < 32; ++k) {
    const Vec3 p = curve.point(u0 + (u1 - u0) * k / 32.0);
    const double s = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
    worst = std::max(worst, (p - (a + s * ab)).norm());
  }
  return worst;
}

double deviation(const SmoothCurve& curve, std::size_t segments) {
  double worst = 0.0;
  for (std::size_t k = 0; k < segments; ++k) {
    worst = std::max(worst, chord_deviation(curve, static_cast<double>(k) / static_cast<double>(segments),
                                            static_cast<double>(k + 1) / static_cast<double>(segments)));
  }
  return worst;
}

}  // namespace

CurveSampling discretize(const SmoothCurve& curve, double tolerance, const std::string& field) {
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) {
    throw InvalidInputError(field, "must be a positive length, got " + format_number(tolerance));
  }
  // Exponential search for an upper bound, then bisection for the fewest segments.
  std::size_t hi = 1;
  while (deviation(curve, hi) > tolerance) {
    if (hi >= max_curve_segments) {
      throw InvalidInputError(field, format_number(tolerance) + " would need more than " +
                                         std::to_string(max_curve_segments) + " segments");
    }
    hi = std::min(2 * hi, max_curve_segments);
  }
  std::size_t lo = hi / 2;  // lo fails (or is 0), hi passes
  while (hi - lo > 1) {
    const std::size_t mid = (lo + hi) / 2;
    (deviation(curve, mid) <= tolerance ? hi : lo) = mid;
  }
  CurveSampling s;
  s.kind = curve.kind;
  s.tolerance = tolerance;
  s.deviation = deviation(curve, hi);
  for (std::size_t k = 0; k <= hi; ++k) {
    const double u = static_cast<double>(k) / static_cast<double>(hi);
    s.points.push_back(curve.point(u));
    s.tangents.push_back(curve.tangent(u));
  }
  return s;
}

Points normal_directions(const Points& trajectory, Points tangents, const Vec3& axis_in, double angle_degrees) {
  const Vec3 axis = axis_in.normalized();
  const Eigen::AngleAxisd turn(angle_degrees * std::numbers::pi / 180.0, axis);
  if (tangents.empty()) {
    for (std::size_t i = 0; i < trajectory.size(); ++i) {
      const std::size_t a = i == 0 ? 0 : i - 1, b = std::min(i + 1, trajectory.size() - 1);
      tangents.push_back(trajectory[b] - trajectory[a]);
    }
  }
  Points out;
  for (std::size_t i = 0; i < tangents.size(); ++i) {
    const Vec3 across = tangents[i] - tangents[i].dot(axis) * axis;
    if (across.norm() <= 1e-12 * std::max(1.0, tangents[i].norm())) {
      throw InvalidInputError("directions.rule",
                              "\"normal\": the trajectory's tangent at point " + std::to_string(i) +
                                  " is parallel to the axis, so it has no normal across the axis");
    }
    out.push_back(turn * axis.cross(across).normalized());
  }
  return out;
}

Points radial_directions(const Points& trajectory, const Vec3& through, const Vec3& axis_in) {
  const Vec3 axis = axis_in.normalized();
  Points out;
  for (std::size_t i = 0; i < trajectory.size(); ++i) {
    Vec3 d = trajectory[i] - through;
    d -= d.dot(axis) * axis;
    if (d.norm() <= 1e-12 * std::max(1.0, trajectory[i].norm())) {
      throw InvalidInputError("directions.through", "\"radial\": trajectory point " + std::to_string(i) +
                                                        " lies on the line through this point along the axis");
    }
    out.push_back(d.normalized());
  }
  return out;
}

}  // namespace phedra
