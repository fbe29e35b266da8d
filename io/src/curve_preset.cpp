#include "phedra/curve_preset.h"

#include "phedra/errors.h"
#include "phedra/json_fields.h"
#include "phedra/number_format.h"

#include <cmath>

namespace phedra {
namespace {

using nlohmann::json;

SmoothCurve helix(const json& spec, const Vec3& axis) {
  const std::string field = "trajectory.helix";
  json_only_keys(spec, field, {"center", "radius", "rise_per_turn", "turns", "start_angle_degrees", "clockwise"});
  HelixSpec h;
  if (spec.contains("center")) h.center = json_vector(spec["center"], field + ".center");
  h.radius = json_number(json_member(spec, field, "radius"), field + ".radius");
  h.rise_per_turn = json_number(json_member(spec, field, "rise_per_turn"), field + ".rise_per_turn");
  h.turns = json_number(json_member(spec, field, "turns"), field + ".turns");
  if (spec.contains("start_angle_degrees")) {
    h.start_angle_degrees = json_number(spec["start_angle_degrees"], field + ".start_angle_degrees");
  }
  if (spec.contains("clockwise")) h.clockwise = json_boolean(spec["clockwise"], field + ".clockwise");
  return helix_curve(h, axis);
}

SmoothCurve spline(const json& spec) {
  const std::string field = "trajectory.spline";
  json_only_keys(spec, field, {"control_points", "degree"});
  const Points control = json_points(json_member(spec, field, "control_points"), field + ".control_points");
  int degree = 3;
  if (spec.contains("degree")) {
    const double d = json_number(spec["degree"], field + ".degree");
    if (d != std::floor(d) || d < 1 || d > 7) {
      throw InvalidInputError(field + ".degree", "expected a whole number from 1 to 7, got " + format_number(d));
    }
    degree = static_cast<int>(d);
  }
  return spline_curve(control, degree);
}

}  // namespace

SmoothCurve smooth_curve(const json& trajectory, const Vec3& axis) {
  json_only_keys(trajectory, "trajectory", {"helix", "spline", "chord_tolerance"});
  const bool has_helix = trajectory.contains("helix"), has_spline = trajectory.contains("spline");
  if (has_helix == has_spline) {
    throw InvalidInputError("trajectory", "a smooth trajectory is either {\"helix\": {...}} or {\"spline\": {...}}");
  }
  return has_helix ? helix(trajectory["helix"], axis) : spline(trajectory["spline"]);
}

CurveSampling trajectory_curve(const json& trajectory, const Vec3& axis) {
  const SmoothCurve curve = smooth_curve(trajectory, axis);
  const double tolerance =
      json_number(json_member(trajectory, "trajectory", "chord_tolerance"), "trajectory.chord_tolerance");
  return discretize(curve, tolerance, "trajectory.chord_tolerance");
}

Points directions_by_rule(const json& rule, const Points& trajectory, Points tangents, const Vec3& axis) {
  if (!rule.is_object() || !rule.contains("rule") || !rule["rule"].is_string()) {
    throw InvalidInputError("directions", "expected an array of [x, y, z] or a rule object {\"rule\": \"normal\"} / "
                                          "{\"rule\": \"radial\", \"through\": [x, y, z]}");
  }
  const std::string name = rule["rule"].get<std::string>();
  if (name == "normal") {
    json_only_keys(rule, "directions", {"rule", "angle_degrees"});
    const double angle =
        rule.contains("angle_degrees") ? json_number(rule["angle_degrees"], "directions.angle_degrees") : 0.0;
    return normal_directions(trajectory, std::move(tangents), axis, angle);
  }
  if (name == "radial") {
    json_only_keys(rule, "directions", {"rule", "through"});
    return radial_directions(trajectory, json_vector(json_member(rule, "directions", "through"), "directions.through"),
                             axis);
  }
  throw InvalidInputError("directions.rule", "unknown rule \"" + name + "\" (known: normal, radial)");
}

}  // namespace phedra
