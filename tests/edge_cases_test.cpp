// Numerical edge cases: the limits themselves, t* next to a limit, scaled
// inputs, nearly parallel planes, nearly equal apexes, long chains.

#include "phedra/errors.h"
#include "phedra/interval_check.h"
#include "phedra/phedron.h"
#include "phedra/preset.h"
#include "support/random_input.h"
#include "phedra/check_report.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace phedra;

namespace {

ControlPolylines default_input() { return load_preset(std::string(PHEDRA_PRESETS_DIR) + "/default.json"); }

/// The configuration of `p` at t as a new input (its trajectory, profile planes and apexes at t).
ControlPolylines configuration_as_input(const PHedron& p, double t) {
  ControlPolylines in = p.input();
  const Points v = p.evaluate(t);
  const GridTopology& g = p.topology();
  for (std::size_t i = 0; i < g.rows(); ++i) {
    in.trajectory[i] = v[g.index(i, 1)];
    Vec3 d = v[g.index(i, 2)] - v[g.index(i, 1)];
    d -= d.dot(in.axis) * in.axis;
    in.directions[i] = d.normalized();
  }
  in.apex_heights = p.apex_heights(t);
  return in;
}

bool all_finite(const Points& v) {
  for (const Vec3& p : v) {
    if (!p.allFinite()) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("evaluate exactly at both limits: finite, planar, isometric", "[edge]") {
  const PHedron p(default_input());
  for (double t : {p.flexion_interval().lower.t, p.flexion_interval().upper.t}) {
    const Points v = p.evaluate(t);
    CHECK(all_finite(v));
  }
  const IntervalCheckReport r = check_over_interval(p, {2});
  CHECK(r.passed());
}

TEST_CASE("any configuration is an input with the same flexion interval, also 1e-9 from a limit", "[edge]") {
  const PHedron p(default_input());
  const FlexionInterval& f = p.flexion_interval();
  for (double t : {p.t_at_fraction(0.1), p.t_at_fraction(0.77), f.upper.t - 1e-9 * f.width(),
                   f.lower.t + 1e-9 * f.width()}) {
    CAPTURE(t);
    const PHedron q(configuration_as_input(p, t));
    CHECK(q.t_star() == Approx(t).margin(1e-12));
    CHECK(q.flexion_interval().lower.t == Approx(f.lower.t).margin(1e-9 * p.model_size()));
    CHECK(q.flexion_interval().upper.t == Approx(f.upper.t).margin(1e-9 * p.model_size()));
    CHECK(q.motion_case() == p.motion_case());
    const IntervalCheckReport r = check_over_interval(q, {50});
    CHECK(r.passed());
  }
}

TEST_CASE("scaled by 1e-6 and 1e6: the same relative results", "[edge]") {
  const ControlPolylines in = default_input();
  const PHedron unit(in);
  const IntervalCheckReport unit_report = check_over_interval(unit, {50});
  for (double scale : {1e-6, 1e6}) {
    CAPTURE(scale);
    ControlPolylines scaled = in;
    for (Vec3& x : scaled.trajectory) x *= scale;
    for (double& h : scaled.apex_heights) h *= scale;
    const PHedron p(scaled);
    CHECK(p.flexion_interval().lower.t / scale == Approx(unit.flexion_interval().lower.t).epsilon(1e-12));
    CHECK(p.flexion_interval().upper.t / scale == Approx(unit.flexion_interval().upper.t).epsilon(1e-12));
    CHECK(p.model_size() / scale == Approx(unit.model_size()).epsilon(1e-12));
    const IntervalCheckReport r = check_over_interval(p, {50});
    CHECK(r.passed());
    CHECK(r.isometry.value / r.model_size <= 1e-12);
    CHECK(unit_report.isometry.value / unit_report.model_size <= 1e-12);
  }
}

TEST_CASE("nearly parallel consecutive planes and nearly equal apexes: a result or a clear error, never NaN", "[edge]") {
  for (double angle : {1e-3, 1e-5, 1e-7, 1e-8}) {
    CAPTURE(angle);
    ControlPolylines in = default_input();
    const Vec3 d = in.directions[4].normalized();
    in.directions[5] = d * std::cos(angle) + in.axis.cross(d) * std::sin(angle);
    try {
      const PHedron p(in);
      const IntervalCheckReport r = check_over_interval(p, {20});
      CHECK(std::isfinite(r.planarity.value));
      CHECK(std::isfinite(r.isometry.value));
      CHECK(all_finite(p.evaluate(p.t_star())));
    } catch (const InvalidInputError& e) {
      CHECK(std::string(e.what()).find("directions[") != std::string::npos);
    }
  }
  for (double gap : {1e-3, 1e-6, 1e-9, 1e-12, 1e-14}) {
    CAPTURE(gap);
    ControlPolylines in = default_input();
    in.apex_heights[3] = in.apex_heights[1] + gap;
    try {
      const PHedron p(in);
      const Points v = p.evaluate(p.t_at_fraction(0.5));
      CHECK(all_finite(v));
    } catch (const InvalidInputError& e) {
      CHECK(std::string(e.what()).find("apex_heights") != std::string::npos);
    }
  }
}

TEST_CASE("near-scissor inputs: a result or a clear error, never NaN", "[edge]") {
  // V_{0,0} at height 0.05; S_0 + S_1 = 2 * 0.05 makes it equidistant from both (scissor).
  for (double offset : {1e-2, 1e-4, 1e-7, 1e-10, 1e-13, 0.0}) {
    for (const char* signs : {"+-+-+", "+++++"}) {
      CAPTURE(offset, signs);
      ControlPolylines in = default_input();
      in.apex_heights[1] = 0.1 - in.apex_heights[0] + offset;
      in.signs = signs_from_string(signs);
      try {
        const PHedron p(in);
        CHECK(all_finite(p.evaluate(p.t_at_fraction(0.5))));
        const IntervalCheckReport r = check_over_interval(p, {10});
        CHECK(std::isfinite(r.isometry.value));
      } catch (const InvalidInputError& e) {
        CHECK(std::string(signs) == "+-+-+");  // only '-' signs are refused near the scissor case
        CHECK((std::string(e.what()).find("scissor") != std::string::npos ||
               std::string(e.what()).find("infinity") != std::string::npos ||
               std::string(e.what()).find("bifurcation") != std::string::npos));
      }
    }
  }
}

TEST_CASE("long chains stay planar and isometric", "[edge]") {
  // A screw-symmetric axial design (every profile plane through the axis): every
  // strip congruent to the first, so the interval does not shrink with m.
  for (std::size_t strips : {500, 10000}) {
    CAPTURE(strips);
    ControlPolylines in;
    for (std::size_t i = 0; i <= strips; ++i) {
      const double a = 0.22 * static_cast<double>(i);
      in.trajectory.push_back(Vec3(3 * std::cos(a), 3 * std::sin(a), 0.35 * static_cast<double>(i)));
      in.directions.push_back(Vec3(std::cos(a), std::sin(a), 0));
    }
    in.apex_heights = {-1.5, 1.0, -0.5, 2.2, 0.4};
    in.signs = {Sign::plus, Sign::plus, Sign::plus};
    const PHedron p(in);
    CHECK(p.flexion_interval().width() > 0.1);
    const IntervalCheckReport r = check_over_interval(p, {10});
    CAPTURE(report_json(r).dump());
    CHECK(r.passed());
    CHECK(r.isometry.value <= 1e-9 * r.model_size);
  }
}
