// The configuration curve through the flexion limits (paper, Remark 3; issue 7
// item 1): the passes of PHedron::configuration_cycle(), the motion on mirrored
// branches, and `phedra info`'s listing.

#include "cli.h"
#include "phedra/design.h"
#include "phedra/errors.h"
#include "phedra/geometry_checks.h"
#include "phedra/gltf_export.h"
#include "phedra/phedron.h"
#include "support/random_input.h"
#include "phedra/design_preset.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <random>
#include <sstream>

using namespace phedra;

namespace {

double largest_distance(const Points& a, const Points& b) {
  double d = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) d = std::max(d, (a[k] - b[k]).norm());
  return d;
}

Points on_branch(const PHedron& p, double t, const std::vector<bool>& flipped, ClosureGap* gap = nullptr) {
  Points v(p.vertex_count());
  p.evaluate(t, flipped, v, gap);
  return v;
}

/// Every pass planar, isometric (and closed for a tube); consecutive passes meet
/// at the limit where the switching strip's two branches coincide.
void check_curve(const PHedron& p) {
  const PHedron::ConfigurationCycle c = p.configuration_cycle();
  const double size = p.model_size();
  CAPTURE(c.passes.size(), c.stop);
  REQUIRE(!c.passes.empty());
  CHECK(c.passes.front().from == p.t_star());
  CHECK(c.passes.front().switched == 0);
  if (c.closed) {
    CHECK(c.passes.back().to == p.t_star());
    CHECK(c.passes.back().flipped == std::vector<bool>(p.topology().rows(), false));
    CHECK((c.passes.size() == 3 || c.passes.size() == 5));
  } else {
    CHECK(c.stop.find("linkage L_0") != std::string::npos);
  }
  const std::vector<Quad> faces = p.topology().faces();
  const std::vector<Segment> segments = p.topology().edges();
  const std::vector<double> lengths = segment_lengths(segments, p.reference());
  for (std::size_t k = 0; k < c.passes.size(); ++k) {
    const PHedron::Pass& pass = c.passes[k];
    CAPTURE(k, pass.from, pass.to, pass.switched);
    const double lo = std::min(pass.from, pass.to), hi = std::max(pass.from, pass.to);
    CHECK(lo >= p.flexion_interval().lower.t);
    CHECK(hi <= p.flexion_interval().upper.t);
    for (double f : {0.0, 0.3, 0.7, 1.0}) {
      const double t = f == 1.0 ? pass.to : pass.from + f * (pass.to - pass.from);
      ClosureGap gap;
      const Points v = on_branch(p, t, pass.flipped, &gap);
      CHECK(planarity(faces, v).value <= 1e-9 * size);
      CHECK(length_deviation(segments, lengths, v).value <= 1e-9 * size);
      if (p.closed()) CHECK(gap.value <= 1e-9 * size);
    }
    if (k > 0) {
      // Continuity at the switch: both branches of the switching strip meet at the
      // limit (up to the square-root conditioning there), and differ inside.
      const PHedron::Pass& before = c.passes[k - 1];
      CHECK(largest_distance(on_branch(p, pass.from, before.flipped), on_branch(p, pass.from, pass.flipped)) <=
            1e-5 * size);
      const double inside = pass.from + 0.5 * (pass.to - pass.from);
      CHECK(largest_distance(on_branch(p, inside, before.flipped), on_branch(p, inside, pass.flipped)) > 1e-6 * size);
    }
  }
}

}  // namespace

TEST_CASE("configuration curve of random P-hedra: planar, isometric, continuous at every switch", "[curve]") {
  std::mt19937_64 rng(314159);
  int redrawn = 0;
  for (std::size_t k = 0; k < 60; ++k) {
    test::RandomInputShape shape;
    shape.profile_vertices = 2 + k % 7;
    shape.strips = 1 + (k * 5) % 20;
    shape.smooth = k % 2 == 0;
    CAPTURE(k);
    const std::optional<PHedron> p = test::draw_phedron([&] { return test::random_input(rng, shape); }, redrawn);
    REQUIRE(p.has_value());
    check_curve(*p);
  }
}

TEST_CASE("configuration curve of the shipped single presets, tubes stay closed on every branch", "[curve]") {
  for (const char* name : {"default", "all-plus", "all-minus", "tilted-axis", "parallelogram-tube",
                           "anti-parallelogram-tube"}) {
    CAPTURE(name);
    const Design d = load_design(std::string(PHEDRA_PRESETS_DIR) + "/" + name + ".json");
    check_curve(d.assembly.base());
  }
}

TEST_CASE("evaluate on a branch: the input branch is evaluate(t), a wrong branch size is an internal error", "[curve]") {
  const Design d = load_design(std::string(PHEDRA_PRESETS_DIR) + "/default.json");
  const PHedron& p = d.assembly.base();
  const double t = p.t_at_fraction(0.4);
  CHECK(largest_distance(on_branch(p, t, std::vector<bool>(p.topology().rows(), false)), p.evaluate(t)) == 0.0);
  Points v(p.vertex_count());
  CHECK_THROWS_AS(p.evaluate(t, std::vector<bool>(2, false), v), Error);
  CHECK_THROWS_AS(p.evaluate(p.flexion_interval().upper.t + 1.0, std::vector<bool>(p.topology().rows(), true), v),
                  OutOfIntervalError);
}

TEST_CASE("phedra info lists the configuration curve", "[curve][cli]") {
  std::ostringstream out, err;
  REQUIRE(cli::run({"info", std::string(PHEDRA_PRESETS_DIR) + "/default.json", "--json"}, out, err) == 0);
  const nlohmann::json j = nlohmann::json::parse(out.str());
  const nlohmann::json& curve = j["configuration_curve"];
  CHECK(curve["closed"] == true);
  CHECK(curve["passes"].size() == 5);
  CHECK(curve["passes"][1]["switched_strip"] == j["limits"][1]["strip"]);
  CHECK(curve["passes"][2]["switched_strip"] == j["limits"][0]["strip"]);
  std::ostringstream text, text_err;
  REQUIRE(cli::run({"info", std::string(PHEDRA_PRESETS_DIR) + "/default.json"}, text, text_err) == 0);
  CHECK(text.str().find("configuration curve: 5 passes, closed") != std::string::npos);
  CHECK(text.str().find("strip 1 switches") != std::string::npos);
}

TEST_CASE("glTF --cycle: the whole curve, pass boundaries as keyframes, hinges within tolerance", "[curve][exports]") {
  // (The default's curve is too long for 250 morph targets at the default
  // tolerance: generate warns then; all-plus's fits.)
  for (const char* name : {"all-plus", "parallelogram-tube"}) {
    for (const bool morph : {false, true}) {
      CAPTURE(name, morph);
      const Design d = load_design(std::string(PHEDRA_PRESETS_DIR) + "/" + name + ".json");
      const PHedron::ConfigurationCycle c = d.assembly.base().configuration_cycle();
      GltfOptions options;
      options.cycle = true;
      options.morph = morph;
      options.binary = false;
      GltfReport report;
      const nlohmann::json j = nlohmann::json::parse(gltf_bytes(d, options, &report));
      CHECK(report.max_opening <= report.tolerance);
      const nlohmann::json& extras = j["asset"]["extras"]["phedra"];
      CHECK(extras["cycle"].size() == c.passes.size());
      const std::vector<double> ts = extras["keyframe_t"].get<std::vector<double>>();
      REQUIRE(ts.size() == report.keyframes);
      CHECK(ts.front() == d.assembly.t_star());
      CHECK(ts.back() == d.assembly.t_star());
      // Every switch is a keyframe: the limits appear once per pass boundary.
      const auto limits = [&](double t) { return std::count(ts.begin(), ts.end(), t); };
      CHECK(limits(d.assembly.flexion_interval().upper.t) >= 2);
      CHECK(limits(d.assembly.flexion_interval().lower.t) >= 2);
      // Animation times increase; one traversal of the interval takes `seconds`.
      const int input = j["animations"][0]["samplers"][0]["input"];
      CHECK(j["accessors"][input]["count"] == ts.size());
      double travelled = 0.0;
      for (const PHedron::Pass& p : c.passes) travelled += std::abs(p.to - p.from);
      CHECK(j["accessors"][input]["max"][0].get<double>() ==
            Approx(travelled / d.assembly.flexion_interval().width() * options.seconds).epsilon(1e-6));
    }
  }
  // Non-glTF outputs refuse --cycle (exit 2, named option), leaving nothing.
  std::ostringstream out2, err2;
  CHECK(cli::run({"generate", std::string(PHEDRA_PRESETS_DIR) + "/default.json", "-o", "/tmp/never.fold", "--cycle"},
                 out2, err2) == 2);
  CHECK(err2.str().find("glTF") != std::string::npos);
  CHECK(err2.str().find("--cycle") != std::string::npos);
  CHECK(!std::filesystem::exists("/tmp/never.fold"));
}

TEST_CASE("arrays follow the base through the limits: closed tubes and shared vertices on every pass", "[curve]") {
  for (const char* name : {"grid-3x3", "row-of-cells", "edge-sharing-pair", "anti-parallelogram-edge-pair",
                           "merged-tube"}) {
    CAPTURE(name);
    const Design d = load_design(std::string(PHEDRA_PRESETS_DIR) + "/" + name + ".json");
    const Assembly& a = d.assembly;
    const PHedron::ConfigurationCycle c = a.base().configuration_cycle();
    CHECK((c.closed || !c.stop.empty()));
    const double tolerance = 1e-9 * a.model_size();
    AssemblyConfiguration on_input, on_pass;
    for (const PHedron::Pass& pass : c.passes) {
      for (double f : {0.25, 0.75}) {
        const double t = pass.from + f * (pass.to - pass.from);
        a.evaluate(t, pass.flipped, on_pass);
        for (std::size_t m = 0; m < a.member_count(); ++m) {
          CAPTURE(m, t);
          CHECK(on_pass.closure[m].value <= tolerance);
        }
        for (const auto& group : a.shared_vertices()) {
          const Vec3& first = on_pass.members[group.front().member][group.front().vertex];
          for (const VertexRef& r : group) CHECK((on_pass.members[r.member][r.vertex] - first).norm() <= tolerance);
        }
        // The members' shapes are kept: every member's edges as at t*.
        for (std::size_t m = 0; m < a.member_count(); ++m) {
          const std::vector<Segment> edges = a.topology(m).edges();
          const std::vector<double> lengths = segment_lengths(edges, a.reference(m));
          CHECK(length_deviation(edges, lengths, on_pass.members[m]).value <= tolerance);
        }
      }
    }
  }
}
