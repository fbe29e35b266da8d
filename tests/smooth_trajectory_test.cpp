// Semi-discrete input (issue 7, item 5): helices and B-splines discretized to a
// chord tolerance, direction rules, their errors, and P-hedra built on them.

#include "phedra/design.h"
#include "phedra/errors.h"
#include "phedra/interval_check.h"
#include "phedra/preset.h"
#include "phedra/smooth_trajectory.h"
#include "phedra/design_preset.h"
#include "phedra/curve_preset.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>

using namespace phedra;
using nlohmann::json;
using Catch::Matchers::Contains;

namespace {

/// The largest distance of the curve from the polyline, densely sampled (1000 points a chord).
double dense_deviation(const std::function<Vec3(double)>& curve, std::size_t segments) {
  double worst = 0.0;
  for (std::size_t k = 0; k < segments; ++k) {
    const double u0 = static_cast<double>(k) / segments, u1 = static_cast<double>(k + 1) / segments;
    const Vec3 a = curve(u0), b = curve(u1);
    for (int s = 1; s < 1000; ++s) {
      const Vec3 p = curve(u0 + (u1 - u0) * s / 1000.0);
      const double f = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
      worst = std::max(worst, (p - (a + f * (b - a))).norm());
    }
  }
  return worst;
}

json helix_trajectory(double radius, double rise, double turns, double tolerance) {
  return {{"helix", {{"radius", radius}, {"rise_per_turn", rise}, {"turns", turns}}}, {"chord_tolerance", tolerance}};
}

void expect_error(const json& preset, const std::string& field, const std::string& text) {
  try {
    preset_from_json(preset);
    FAIL("no error for " << field);
  } catch (const InvalidInputError& e) {
    CHECK(e.field() == field);
    CHECK_THAT(e.what(), Contains(text));
  }
}

json base_preset() {
  return {{"name", "smooth"},
          {"trajectory", helix_trajectory(3.0, 4.0, 0.3, 0.01)},
          {"directions", {{"rule", "normal"}}},
          {"apex_heights", {-1.5, 1.0, -0.5, 2.2, 0.4}},
          {"signs", "+++"}};
}

}  // namespace

TEST_CASE("a circle arc gets the fewest chords within the tolerance", "[smooth]") {
  for (double tolerance : {0.1, 0.01, 0.003, 1e-4}) {
    for (double turns : {0.25, 1.0, 2.5}) {
      CAPTURE(tolerance, turns);
      const CurveSampling s = trajectory_curve(helix_trajectory(2.0, 0.0, turns, tolerance), Vec3::UnitZ());
      // A chord of angle D deviates 2 (1 - cos(D / 2)) from a circle of radius 2.
      const double step = 2.0 * std::acos(1.0 - tolerance / 2.0);
      const auto expected = static_cast<std::size_t>(std::ceil(2.0 * std::numbers::pi * turns / step - 1e-9));
      CHECK(s.points.size() - 1 == expected);
      CHECK(s.deviation <= tolerance);
      for (const Vec3& p : s.points) CHECK(std::hypot(p.x(), p.y()) == Approx(2.0));
    }
  }
}

TEST_CASE("helices about any axis: on the helix, within the tolerance, tangents right", "[smooth]") {
  const Vec3 axis = Vec3(1.0, -2.0, 0.5).normalized();
  const json trajectory = {{"helix",
                            {{"center", {1.0, 2.0, 3.0}},
                             {"radius", 1.5},
                             {"rise_per_turn", -2.0},
                             {"turns", 1.7},
                             {"start_angle_degrees", 33},
                             {"clockwise", true}}},
                           {"chord_tolerance", 0.002}};
  const CurveSampling s = trajectory_curve(trajectory, axis);
  const Vec3 c(1.0, 2.0, 3.0);
  for (std::size_t k = 0; k < s.points.size(); ++k) {
    const Vec3 r = s.points[k] - c;
    CHECK((r - r.dot(axis) * axis).norm() == Approx(1.5));  // on the cylinder
    // Rises -2 a turn: after the whole curve, -3.4 along the axis.
    CHECK(r.dot(axis) == Approx(-3.4 * static_cast<double>(k) / static_cast<double>(s.points.size() - 1)).margin(1e-12));
  }
  // Tangents: the exact derivative (along the axis -3.4; around it 1.5 * 2 pi * 1.7).
  CHECK(s.tangents.size() == s.points.size());
  CHECK(s.tangents.front().dot(axis) == Approx(-3.4));
  CHECK(s.tangents.front().norm() == Approx(std::hypot(-3.4, 1.5 * 2 * std::numbers::pi * 1.7)));
}

TEST_CASE("B-splines: clamped ends, within the tolerance by a dense check, fewest chords", "[smooth]") {
  const json control = json::array({{0, 0, 0}, {2, 1, 0.5}, {4, -1, 1}, {6, 2, 1.2}, {8, 0, 2}, {9, 3, 2.5}});
  for (int degree : {1, 2, 3, 5}) {
    for (double tolerance : {0.05, 0.005}) {
      CAPTURE(degree, tolerance);
      const json trajectory = {{"spline", {{"control_points", control}, {"degree", degree}}},
                               {"chord_tolerance", tolerance}};
      const CurveSampling s = trajectory_curve(trajectory, Vec3::UnitZ());
      CHECK((s.points.front() - Vec3(0, 0, 0)).norm() < 1e-12);
      CHECK((s.points.back() - Vec3(9, 3, 2.5)).norm() < 1e-12);
      const SmoothCurve curve = smooth_curve(trajectory, Vec3::UnitZ());
      const std::size_t n = s.points.size() - 1;
      CHECK(dense_deviation(curve.point, n) <= tolerance * 1.01);
      if (n > 1) CHECK(dense_deviation(curve.point, n - 1) > tolerance * 0.99);
    }
  }
  // Four control points, degree 3: the cubic Bezier curve, point and tangent.
  const Points p{Vec3(0, 0, 0), Vec3(1, 2, 0), Vec3(3, 2, 1), Vec3(4, 0, 1)};
  const SmoothCurve bezier = smooth_curve(
      {{"spline", {{"control_points", {{0, 0, 0}, {1, 2, 0}, {3, 2, 1}, {4, 0, 1}}}}}, {"chord_tolerance", 0.01}},
      Vec3::UnitZ());
  for (double u : {0.0, 0.1, 0.37, 0.5, 0.9, 1.0}) {
    const double v = 1.0 - u;
    const Vec3 point = v * v * v * p[0] + 3 * v * v * u * p[1] + 3 * v * u * u * p[2] + u * u * u * p[3];
    const Vec3 tangent = 3 * (v * v * (p[1] - p[0]) + 2 * v * u * (p[2] - p[1]) + u * u * (p[3] - p[2]));
    CAPTURE(u);
    CHECK((bezier.point(u) - point).norm() < 1e-14);
    CHECK((bezier.tangent(u) - tangent).norm() < 1e-13);
  }
  // Degree 1 through collinear points: one chord is exact.
  const CurveSampling line = trajectory_curve(
      {{"spline", {{"control_points", {{0, 0, 0}, {1, 1, 1}, {3, 3, 3}}}, {"degree", 1}}}, {"chord_tolerance", 1e-9}},
      Vec3::UnitZ());
  CHECK(line.points.size() == 2);
}

TEST_CASE("discretize: dense checks of the deviation and of minimality", "[smooth]") {
  const SmoothCurve wave{"wave", [](double u) { return Vec3(10 * u, std::sin(6 * u), 0.3 * std::cos(11 * u)); },
                         [](double u) { return Vec3(10, 6 * std::cos(6 * u), -3.3 * std::sin(11 * u)); }};
  for (double tolerance : {0.05, 0.01, 0.001}) {
    CAPTURE(tolerance);
    const CurveSampling s = discretize(wave, tolerance, "t");
    const std::size_t n = s.points.size() - 1;
    CHECK(dense_deviation(wave.point, n) <= tolerance * 1.01);
    CHECK(dense_deviation(wave.point, n - 1) > tolerance * 0.99);
    for (std::size_t k = 0; k <= n; ++k) {
      const double u = static_cast<double>(k) / static_cast<double>(n);
      CHECK((s.points[k] - wave.point(u)).norm() < 1e-15);
      CHECK((s.tangents[k] - wave.tangent(u)).norm() < 1e-12);
    }
  }
}

TEST_CASE("direction rules: normal (turned) and radial", "[smooth]") {
  const Vec3 axis = Vec3::UnitZ();
  const Points trajectory{Vec3(3, 0, 0), Vec3(3, 1, 0.2), Vec3(2.5, 2, 0.4), Vec3(1.5, 2.6, 0.6)};
  const Points normal = directions_by_rule({{"rule", "normal"}}, trajectory, {}, axis);
  REQUIRE(normal.size() == 4);
  for (std::size_t i = 0; i < 4; ++i) {
    const std::size_t a = i == 0 ? 0 : i - 1, b = std::min<std::size_t>(i + 1, 3);
    const Vec3 tangent = trajectory[b] - trajectory[a];
    CHECK(normal[i].norm() == Approx(1.0));
    CHECK(std::abs(normal[i].dot(axis)) < 1e-15);
    CHECK(std::abs(normal[i].dot(tangent)) < 1e-12);
  }
  const Points turned = directions_by_rule({{"rule", "normal"}, {"angle_degrees", 90}}, trajectory, {}, axis);
  for (std::size_t i = 0; i < 4; ++i) CHECK(std::abs(turned[i].dot(normal[i])) < 1e-12);
  const Points radial = directions_by_rule({{"rule", "radial"}, {"through", {0, 0, 5}}}, trajectory, {}, axis);
  for (std::size_t i = 0; i < 4; ++i) {
    CHECK((radial[i] - Vec3(trajectory[i].x(), trajectory[i].y(), 0).normalized()).norm() < 1e-12);
  }
}

TEST_CASE("smooth presets build P-hedra and tubes that pass the checks, and converge", "[smooth]") {
  const ControlPolylines input = preset_from_json(base_preset());
  CHECK(input.trajectory.size() > 5);
  CHECK_THAT(input.trajectory_source, Contains("helix"));
  const PHedron p(input);
  const IntervalCheckReport r = check_over_interval(p);
  CHECK(r.passed());
  // The shipped helix tube: closed over the whole interval.
  const Design tube = load_design(std::string(PHEDRA_PRESETS_DIR) + "/helix-tube.json");
  CHECK(tube.assembly.closed(0));
  // Semi-discrete limit: the flexion interval converges as the tolerance shrinks.
  std::vector<std::pair<double, double>> intervals;
  for (double tolerance : {1e-2, 1e-3, 1e-4}) {
    json preset = base_preset();
    preset["trajectory"]["chord_tolerance"] = tolerance;
    const PHedron q(preset_from_json(preset));
    intervals.push_back({q.flexion_interval().lower.t, q.flexion_interval().upper.t});
  }
  const double first = std::abs(intervals[1].first - intervals[0].first) + std::abs(intervals[1].second - intervals[0].second);
  const double second = std::abs(intervals[2].first - intervals[1].first) + std::abs(intervals[2].second - intervals[1].second);
  CHECK(second < 0.5 * first);
  // The preset written back holds the discretized polyline and rebuilds the same P-hedron.
  const ControlPolylines again = preset_from_json(preset_to_json(input));
  CHECK(again.trajectory == input.trajectory);
  CHECK(again.directions == input.directions);
}

TEST_CASE("smooth trajectories: one error per bad field", "[smooth]") {
  auto with = [](const std::function<void(json&)>& change) {
    json p = base_preset();
    change(p);
    return p;
  };
  expect_error(with([](json& p) { p["trajectory"]["helix"]["radius"] = 0; }), "trajectory.helix.radius", "positive");
  expect_error(with([](json& p) { p["trajectory"]["helix"]["turns"] = -1; }), "trajectory.helix.turns", "positive");
  expect_error(with([](json& p) { p["trajectory"]["helix"].erase("rise_per_turn"); }), "trajectory.helix.rise_per_turn",
               "missing");
  expect_error(with([](json& p) { p["trajectory"]["helix"]["pitch"] = 1; }), "trajectory.helix.pitch", "unknown key");
  expect_error(with([](json& p) { p["trajectory"]["helix"]["clockwise"] = 1; }), "trajectory.helix.clockwise",
               "true or false");
  expect_error(with([](json& p) { p["trajectory"]["chord_tolerance"] = 0; }), "trajectory.chord_tolerance", "positive");
  expect_error(with([](json& p) { p["trajectory"].erase("chord_tolerance"); }), "trajectory.chord_tolerance", "missing");
  expect_error(with([](json& p) { p["trajectory"]["chord_tolerance"] = 1e-12; }), "trajectory.chord_tolerance",
               "more than 100000 segments");
  expect_error(with([](json& p) { p["trajectory"]["spline"] = {{"control_points", json::array()}}; }), "trajectory",
               "either");
  expect_error(with([](json& p) {
                 p["trajectory"] = {{"spline", {{"control_points", {{0, 0, 0}, {1, 0, 0}}}}}, {"chord_tolerance", 0.1}};
               }),
               "trajectory.spline.control_points", "at least 4 control points");
  expect_error(with([](json& p) {
                 p["trajectory"] = {{"spline", {{"control_points", {{0, 0, 0}, {1, 0, 0}, {2, 1, 0}}}, {"degree", 2.5}}},
                                    {"chord_tolerance", 0.1}};
               }),
               "trajectory.spline.degree", "whole number");
  expect_error(with([](json& p) {
                 p["trajectory"] = {{"spline", {{"control_points", {{0, 0, 0}, {1, 0}, {2, 1, 0}}}, {"degree", 1}}},
                                    {"chord_tolerance", 0.1}};
               }),
               "trajectory.spline.control_points[1]", "[x, y, z]");
  expect_error(with([](json& p) { p["directions"] = {{1, 0, 0}, {0, 1, 0}}; }), "directions", "direction rule");
  expect_error(with([](json& p) { p["directions"] = {{"rule", "tangent"}}; }), "directions.rule", "unknown rule");
  expect_error(with([](json& p) { p["directions"] = {{"rule", "radial"}}; }), "directions.through", "missing");
  expect_error(with([](json& p) { p["directions"] = {{"rule", "radial"}, {"through", {3, 0, 0}}}; }),
               "directions.through", "trajectory point 0");
  // A polyline with a segment along the axis has no normal there.
  expect_error(with([](json& p) {
                 p["trajectory"] = {{3, 0, 0}, {3, 0, 1}, {3, 0, 2}};
                 p["directions"] = {{"rule", "normal"}};
               }),
               "directions.rule", "parallel to the axis");
}
