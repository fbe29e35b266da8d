// Size-bounded buildability (issue 24): oversized panels and slivers, and the
// growth bound on the motion, checked on hand-made quads, on random designs
// (the bound holds at every sample of the reported interval, and ends it where
// it binds) and from the command line.

#include "support/cli_run.h"
#include "support/test_files.h"
#include "phedra/buildability.h"
#include "phedra/design_preset.h"
#include "phedra/field_hints.h"
#include "phedra/panel_nets.h"
#include "phedra/panel_size.h"
#include "phedra/self_intersection.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <random>
#include <string>

using phedra::test::data;
using phedra::test::phedra_cli;
using phedra::test::presets;
using phedra::test::read_json;
using phedra::test::Run;
using Catch::Matchers::Contains;
using namespace phedra;
using json = nlohmann::json;

namespace {

/// The bounding-box diagonal of the design's mesh at t.
double size_at(const Design& d, const AssemblyMesh& mesh, double t) {
  AssemblyConfiguration c;
  d.assembly.evaluate(t, c);
  return bounding_diagonal(mesh.positions(c));
}

/// Shipped presets with their heights disturbed: designs of every kind, some growing a lot.
json disturbed(std::mt19937_64& rng, int k) {
  static const char* names[] = {"default", "all-plus", "all-minus", "parallelogram-tube", "row-of-cells"};
  json p = read_json(presets + "/" + names[k % 5] + ".json");
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto disturb = [&](json& list) {
    for (json& h : list) h = h.get<double>() + 0.4 * unit(rng);
  };
  if (p.contains("apex_heights")) disturb(p["apex_heights"]);
  if (p.contains("tube")) disturb(p["tube"]["apex_heights"]);
  return p;
}

}  // namespace

TEST_CASE("panel proportions: edge ratio to the median, aspect, area of any simple quad", "[size-bounds]") {
  const Points x{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),          // unit square
                 Vec3(0, 0, 1), Vec3(1000, 0, 1), Vec3(1000, 0.5, 1), Vec3(0, 0.5, 1)};  // a 1000 x 0.5 strip
  const std::vector<Quad> faces{{0, 1, 2, 3}, {0, 1, 2, 3}, {4, 5, 6, 7}};
  const std::vector<PanelProportions> p = panel_proportions(x, faces);
  CHECK(p[0].longest_edge == Approx(1.0));
  CHECK(p[0].aspect == Approx(1.0));
  CHECK(p[0].edge_ratio == Approx(1.0));       // the median is the unit square's edge
  CHECK(p[2].edge_ratio == Approx(1000.0));
  CHECK(p[2].aspect == Approx(0.5e-3));
  CHECK(p[2].longest == 0);
  // A triangle given with a repeated corner, and a dart (one reflex corner).
  CHECK(quad_area({Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0), Vec3(0, 2, 0)}) == Approx(2.0));
  CHECK(quad_area({Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0.5, 0.5, 0), Vec3(0, 2, 0)}) == Approx(1.0));
  CHECK(bounding_diagonal(x) == Approx(std::sqrt(1000.0 * 1000.0 + 1.0 + 1.0)));
}

TEST_CASE("an oversized panel is not buildable, with its cause and the fields to change", "[size-bounds]") {
  const json preset = read_json(data + "/oversized-panels.json");
  const Design d = design_from_json(preset);
  const BuildabilityReport r = assess_buildability(d, &preset);
  CHECK(!r.buildable());
  CHECK(!r.interval());
  REQUIRE(r.count(PanelShape::oversized) == 3);
  for (const PanelDiagnosis& p : r.invalid) {
    CHECK(p.rule.cause == PanelCause::oversized);
    CHECK(p.strip == 7);
    CHECK_THAT(p.why, Contains("times the median panel's longest edge (at most 100)"));
    CHECK(!p.hints.empty());
  }
  CHECK(r.to_json()["oversized"] == 3);
  CHECK(r.file_json()["invalid_shapes"][0] == "oversized");
  // Its size compared with the bounded panels: the model size is 1e8, the other panels' about 60.
  CHECK(d.assembly.model_size() > 1e8);
  CHECK(bounded_model_size(d) < 100.0);
  // The same panels are slivers too (1.4e8 long, a few units wide); without either
  // bound: simple panels, buildable over part of the interval.
  BuildabilityOptions edge_only;
  edge_only.bounds.max_edge_ratio = 0.0;
  CHECK(assess_buildability(d, nullptr, edge_only).count(PanelShape::sliver) == 3);
  BuildabilityOptions none;
  none.bounds = {0.0, 0.0, 0.0};
  const BuildabilityReport unbounded = assess_buildability(d, nullptr, none);
  CHECK(unbounded.panels_simple());
  CHECK(unbounded.interval());
  // Each hint, followed a little past its first-order change, shrinks that panel's longest edge a hundredfold.
  const PanelDiagnosis& first = r.invalid[0];
  const PanelNets before = panel_nets(d.assembly, first.member, first.strip * d.assembly.topology(0).face_columns() + first.column);
  for (const FieldHint& h : first.hints) {
    json changed = preset;
    const std::vector<DesignField> fields = design_fields(preset, 1.0);
    const auto field = std::find_if(fields.begin(), fields.end(), [&](const DesignField& f) { return f.name == h.field; });
    REQUIRE(field != fields.end());
    changed.at(field->pointer) = h.value + 1.2 * h.change;
    const Design after = design_from_json(changed);
    const PanelNets now = panel_nets(after.assembly, first.member, first.strip * after.assembly.topology(0).face_columns() + first.column);
    INFO(describe(h));
    CHECK(longest_edge_squared(now.general) < 1e-4 * longest_edge_squared(before.general));
  }
}

TEST_CASE("a sliver is not buildable", "[size-bounds]") {
  // The default preset with the bound raised above its thinnest panel: every panel thinner is a sliver.
  const json preset = read_json(presets + "/default.json");
  const Design d = design_from_json(preset);
  const AssemblyMesh mesh = panel_mesh(d);
  AssemblyConfiguration c;
  d.assembly.evaluate(d.assembly.t_star(), c);
  const std::vector<PanelProportions> p = panel_proportions(mesh.positions(c), mesh.faces);
  double thinnest = 1.0;
  for (const PanelProportions& q : p) thinnest = std::min(thinnest, q.aspect);
  BuildabilityOptions options;
  options.bounds.min_aspect = 1.01 * thinnest;
  const BuildabilityReport r = assess_buildability(d, &preset, options);
  REQUIRE(r.count(PanelShape::sliver) >= 1);
  CHECK(r.invalid[0].rule.cause == PanelCause::sliver);
  CHECK_THAT(r.invalid[0].why, Contains("it is a sliver: its area is"));
  CHECK_THAT(r.summary(), Contains("cannot be built (") && Contains("sliver"));
  CHECK(assess_buildability(d).buildable());  // with the default bound (1e-3) it is fine
}

TEST_CASE("the growth bound holds at every sample of the buildable interval and ends it where it binds",
          "[size-bounds]") {
  std::mt19937_64 rng(24);
  int bound_ended = 0, designs = 0;
#ifdef PHEDRA_SANITIZE_BUILD
  const int drawn = 12;  // the code paths (a sweep is about 10x slower there)
#else
  const int drawn = 40;
#endif
  for (int k = 0; k < drawn; ++k) {
    const json preset = disturbed(rng, k);
    std::optional<Design> d;
    try {
      d = design_from_json(preset);
    } catch (const Error&) {
      continue;
    }
    ++designs;
    const AssemblyMesh mesh = panel_mesh(*d);
    const double at_star = size_at(*d, mesh, d->assembly.t_star());
    for (double growth : {1.002, 1.01, 10.0}) {
      SelfIntersectionOptions options;
      options.samples_per_side = 60;
      options.max_growth = growth;
      const SelfIntersectionReport r = find_self_intersections(*d, options);
      if (r.at_t_star) continue;
      for (int s = 0; s <= 40; ++s) {
        const double t = s == 40 ? r.free_upper : r.free_lower + (r.free_upper - r.free_lower) * s / 40.0;
        CHECK(size_at(*d, mesh, t) <= growth * at_star * (1.0 + 1e-9));
      }
      for (const auto& [end, hit] : {std::pair{r.free_lower, r.lower}, std::pair{r.free_upper, r.upper}}) {
        if (!hit || hit->kind != Collision::Kind::growth) continue;
        ++bound_ended;
        CHECK(size_at(*d, mesh, end) == Approx(growth * at_star).epsilon(1e-6));
        CHECK(hit->growth == growth);
        CHECK_THAT(describe(*hit, false), Contains("grows past"));
      }
    }
  }
  CHECK(designs >= drawn * 3 / 4);
  CHECK(bound_ended >= drawn / 4);  // the bound binds on many of them at 1.002 and 1.01 (folding changes the bounding box by a few per cent)
}

TEST_CASE("check, intersections and repair: --max-growth and --max-panel-ratio", "[size-bounds][cli]") {
  const std::string oversized = data + "/oversized-panels.json";
  const Run c = phedra_cli({"check", oversized});
  CHECK(c.code == 1);
  CHECK_THAT(c.out, Contains("buildability: not buildable: 3 of 56 panels cannot be built (3 oversized: panels 51, 52, 53)"));
  CHECK_THAT(c.out, Contains("panel 51 (strip 7, column 2) is oversized: its transversal edge V_{7,2} V_{8,2} is"));
  CHECK_THAT(c.out, Contains("    change: "));
  const Run unbounded = phedra_cli({"check", oversized, "--max-panel-ratio", "0"});
  CHECK_THAT(unbounded.out, Contains("(3 slivers: panels 51, 52, 53)") && Contains("it is a sliver: its area is"));
  // The default preset grows by 2 % over its motion (its bounding-box diagonal 12.77 at t*, 13.02 at most): 1.01 ends its interval.
  const Run fine = phedra_cli({"check", presets + "/default.json"});
  CHECK(fine.code == 0);
  const Run tight = phedra_cli({"intersections", presets + "/default.json", "--max-growth", "1.01"});
  CHECK(tight.code == 0);
  CHECK_THAT(tight.out, Contains("the design grows past 1.01 times its size at t*"));
  const Run j = phedra_cli({"intersections", presets + "/default.json", "--max-growth", "1.01", "--json"});
  const json report = json::parse(j.out);
  CHECK((report["lower"]["kind"] == "growth" || report["upper"]["kind"] == "growth"));
  const Run bad = phedra_cli({"check", oversized, "--max-growth", "-1"});
  CHECK(bad.code == 2);
  CHECK_THAT(bad.err, Contains("--max-growth"));
}
