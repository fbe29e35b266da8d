// Self-intersection (issue 7, item 3): the triangle test, panel shapes, the
// sweep against a brute-force search on random designs and the shipped presets,
// and the command line (phedra intersections, generate --no-self-intersection).

#include "support/test_files.h"
#include "support/cli_run.h"
#include "phedra/errors.h"
#include "phedra/self_intersection.h"
#include "phedra/tube.h"
#include "support/random_input.h"
#include "phedra/design_preset.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

using phedra::test::data;
using phedra::test::presets;

using namespace phedra;
using test::phedra_cli;
using test::Run;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {


Triangle tri(Vec3 a, Vec3 b, Vec3 c) { return {a, b, c}; }

/// Every pair of valid panels that share no edge, tested without broad phase:
/// the deepest penetration at x.
double brute_force_depth(const AssemblyMesh& mesh, const Points& x, const std::vector<bool>& valid) {
  double deepest = -1.0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (!valid[f]) continue;
    for (std::size_t g = f + 1; g < mesh.faces.size(); ++g) {
      if (!valid[g]) continue;
      const Quad& a = mesh.faces[f];
      const Quad& b = mesh.faces[g];
      bool shares_edge = false;
      for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) {
          shares_edge = shares_edge || (a[i] == b[(j + 1) % 4] && a[(i + 1) % 4] == b[j]) ||
                        (a[i] == b[j] && a[(i + 1) % 4] == b[(j + 1) % 4]);
        }
      }
      if (shares_edge) continue;
      for (const Triangle& p : panel_triangles({x[a[0]], x[a[1]], x[a[2]], x[a[3]]})) {
        for (const Triangle& q : panel_triangles({x[b[0]], x[b[1]], x[b[2]], x[b[3]]})) {
          deepest = std::max(deepest, triangle_penetration(p, q));
        }
      }
    }
  }
  return deepest;
}

std::vector<bool> valid_panels(const Design& design, const AssemblyMesh& mesh) {
  std::vector<bool> valid(mesh.faces.size(), true);
  for (const InvalidPanel& p : invalid_panels(design)) valid[p.panel.face] = false;
  return valid;
}

Points positions(const Design& design, const AssemblyMesh& mesh, double t) {
  AssemblyConfiguration c;
  design.assembly.evaluate(t, c);
  return mesh.positions(c);
}

/// The angle (degrees) between the two panels' normals, oriented consistently
/// across their common edge: 180 when they lie folded onto each other.
double normal_angle(const AssemblyMesh& mesh, const Points& x, std::size_t f, std::size_t g) {
  auto normal = [&](std::size_t k) {
    const Quad& q = mesh.faces[k];
    return ((x[q[2]] - x[q[0]]).cross(x[q[3]] - x[q[1]])).normalized();
  };
  return std::acos(std::clamp(normal(f).dot(normal(g)), -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

/// The report's claims, checked independently.
void check_report(const Design& design, const SelfIntersectionReport& r) {
  const AssemblyMesh mesh = panel_mesh(design);
  const std::vector<bool> valid = valid_panels(design, mesh);
  const double tolerance = 1e-9 * r.model_size;
  CAPTURE(r.t_lambda, r.t_star, r.t_mu, r.free_lower, r.free_upper);
  if (r.at_t_star) {
    const Points x = positions(design, mesh, r.t_star);
    if (r.at_t_star->kind == Collision::Kind::panels) CHECK(brute_force_depth(mesh, x, valid) > tolerance);
    return;
  }
  CHECK(r.t_lambda <= r.free_lower);
  CHECK(r.free_lower <= r.t_star);
  CHECK(r.t_star <= r.free_upper);
  CHECK(r.free_upper <= r.t_mu);
  // No penetration anywhere inside the free interval (brute force, 9 places).
  for (int k = 0; k <= 8; ++k) {
    const double t = k == 8 ? r.free_upper : r.free_lower + (r.free_upper - r.free_lower) * k / 8.0;
    CAPTURE(t);
    CHECK(brute_force_depth(mesh, positions(design, mesh, t), valid) <= tolerance);
  }
  // What ends it is really there.
  const double width = r.t_mu - r.t_lambda;
  for (const auto& [collision, direction] : {std::pair{r.lower, -1.0}, std::pair{r.upper, 1.0}}) {
    if (!collision) continue;
    const Collision& c = *collision;
    if (c.kind == Collision::Kind::hinge) {
      // Folded onto each other: the consistently oriented normals are opposite.
      CHECK(normal_angle(mesh, positions(design, mesh, c.t), c.a.face, c.b.face) > 179.9);
    } else {
      const double past = std::clamp(c.t + direction * 1e-6 * width, r.t_lambda, r.t_mu);
      CHECK(brute_force_depth(mesh, positions(design, mesh, past), valid) > 0.0);
    }
  }
}

}  // namespace

TEST_CASE("triangle_penetration: crossing, apart and every kind of contact", "[self-intersection]") {
  const Triangle floor = tri({0, 0, 0}, {4, 0, 0}, {0, 4, 0});
  // A triangle piercing the floor.
  CHECK(triangle_penetration(floor, tri({1, 1, -1}, {1, 1, 1}, {2, 0.5, 1})) > 0.1);
  CHECK(triangle_penetration(tri({1, 1, -1}, {1, 1, 1}, {2, 0.5, 1}), floor) > 0.1);
  // Apart, above.
  CHECK(triangle_penetration(floor, tri({1, 1, 1}, {2, 1, 1}, {1, 2, 2})) < 0.0);
  // Standing on the floor along an edge (a T): contact.
  CHECK(triangle_penetration(floor, tri({1, 1, 0}, {2, 1, 0}, {1.5, 1, 2})) == Approx(0.0).margin(1e-15));
  // Touching at one corner only.
  CHECK(triangle_penetration(floor, tri({1, 1, 0}, {2, 2, 1}, {1, 3, 1})) == Approx(0.0).margin(1e-15));
  // Lying flat on it (coplanar, overlapping): contact.
  CHECK(triangle_penetration(floor, tri({1, 1, 0}, {3, 0.5, 0}, {1, 2, 0})) == 0.0);
  // Sharing a corner and cutting through from there.
  CHECK(triangle_penetration(floor, tri({0, 0, 0}, {2, 1, 1}, {1, 2, -1})) > 0.1);
  // Sharing a corner, both others on one side: contact.
  CHECK(triangle_penetration(floor, tri({0, 0, 0}, {2, 1, 1}, {1, 2, 1})) == Approx(0.0).margin(1e-15));
  // No area: nothing to cut.
  CHECK(triangle_penetration(floor, tri({1, 1, -1}, {1, 1, 1}, {1, 1, 1})) == 0.0);
  // Crossing near the edge of the floor: the depth is the shorter common segment.
  const double depth = triangle_penetration(floor, tri({3.9, -1, -1}, {3.9, -1, 1}, {3.9, 1, 0}));
  CHECK(depth > 0.0);
  CHECK(depth < 0.2);
}

TEST_CASE("panel_shape: convex, non-convex, bow-tie, degenerate, and triangles that cover the panel", "[self-intersection]") {
  CHECK(panel_shape({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)}) == PanelShape::convex);
  CHECK(panel_shape({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 0, 0)}) == PanelShape::convex);  // a triangle
  CHECK(panel_shape({Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}) == PanelShape::bow_tie);
  CHECK(panel_shape({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0)}) == PanelShape::degenerate);
  // A dart: reflex corner 2; its triangles must lie inside (their areas add up to the dart's).
  const PanelCorners dart{Vec3(0, 0, 1), Vec3(4, 0, 1), Vec3(1, 1, 1), Vec3(0, 4, 1)};
  CHECK(panel_shape(dart) == PanelShape::non_convex);
  double area = 0.0;
  for (const Triangle& t : panel_triangles(dart)) area += 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).norm();
  CHECK(area == Approx(4.0));  // shoelace: (0,0),(4,0),(1,1),(0,4) -> 4
  // Rotated into space, the same shape.
  const Mat3 r = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  PanelCorners turned = dart;
  for (Vec3& v : turned) v = r * v + Vec3(5, -2, 1);
  CHECK(panel_shape(turned) == PanelShape::non_convex);
}

TEST_CASE("the sweep agrees with a brute-force search on random P-hedra and tubes", "[self-intersection]") {
  // Random P-hedra often cut through themselves already at t* (confirmed by an
  // independent edge-through-triangle search); short smooth parallelogram tubes
  // often fold freely: both paths.
  std::mt19937_64 rng(20261123);
  int redrawn = 0, at_t_star = 0, swept = 0;
  for (int k = 0; k < 36; ++k) {
    const bool tube = k % 3 != 0;
    test::RandomInputShape shape;
    shape.strips = tube ? 2 + k % 4 : 4 + k % 5;
    shape.profile_vertices = tube ? 5 : 3 + k % 3;
    shape.smooth = tube || k % 2 == 0;
    const std::optional<PHedron> p = test::draw_phedron(
        [&] {
          ControlPolylines input = test::random_input(rng, shape);
          if (tube) {
            std::uniform_real_distribution<double> height(-3.0, 3.0);
            TubeHeights z;
            do {
              z = {height(rng), height(rng), height(rng), height(rng)};
            } while (std::abs(z[0] - z[1]) < 0.3 || std::abs(z[1] - z[2]) < 0.3 || std::abs(z[2] - z[3]) < 0.3 ||
                     std::abs(z[3] - z[0]) < 0.3 || std::abs(z[0] - z[2]) < 0.3 || std::abs(z[1] - z[3]) < 0.3);
            set_tube_profile(input, TubeType::parallelogram, z);
          }
          return input;
        },
        redrawn);
    REQUIRE(p);
    const Design design{Assembly(*p), false, tube ? "parallelogram tube" : "open P-hedron"};
    SelfIntersectionOptions options;
    options.samples_per_side = 60;
    const SelfIntersectionReport r = find_self_intersections(design, options);
    CAPTURE(k, tube);
    check_report(design, r);
    at_t_star += r.at_t_star ? 1 : 0;
    swept += r.at_t_star ? 0 : 1;
  }
  CHECK(at_t_star > 0);
  CHECK(swept > 3);
}

TEST_CASE("the sweep on every shipped preset: tubes, pairs and arrays", "[self-intersection]") {
  for (const auto& entry : fs::directory_iterator(presets)) {
    if (entry.path().extension() != ".json" || entry.path().filename() == "preset.schema.json") continue;
    CAPTURE(entry.path().string());
    const Design design = load_design(entry.path());
    const SelfIntersectionReport r = find_self_intersections(design, {.samples_per_side = 80});
    check_report(design, r);
  }
  // A parallelogram tube folds without collision over its whole interval.
  const SelfIntersectionReport tube = find_self_intersections(load_design(presets + "/parallelogram-tube.json"));
  CHECK(tube.intersection_free());
  CHECK(tube.invalid_panels.empty());
  // The shipped presets are buildable: the 3 x 3 grid (interior walls included) is free over its whole interval.
  const SelfIntersectionReport grid = find_self_intersections(load_design(presets + "/grid-3x3.json"));
  CHECK(grid.intersection_free());
  // A design whose hinge folds through inside the interval, above t* (t* is t_lambda).
  const Design partly = load_design(data + "/partly-buildable.json");
  const SelfIntersectionReport r = find_self_intersections(partly);
  check_report(partly, r);
  REQUIRE(r.upper);
  CHECK(r.upper->kind == Collision::Kind::hinge);
  CHECK(r.free_upper < r.t_mu - 0.3 * (r.t_mu - r.t_lambda));
  CHECK(r.free_lower == r.t_lambda);
}

TEST_CASE("a design that cuts through itself at t*", "[self-intersection]") {
  const Design design = load_design(data + "/self-intersecting.json");
  const SelfIntersectionReport r = find_self_intersections(design);
  REQUIRE(r.at_t_star);
  CHECK(r.at_t_star->kind == Collision::Kind::panels);
  CHECK(!r.intersection_free());
  check_report(design, r);
  CHECK_THROWS_AS(intersection_free_interval(r), InvalidInputError);
  REQUIRE(self_intersection_at_t_star(design));
  CHECK(self_intersection_at_t_star(design)->a.face == r.at_t_star->a.face);
}

TEST_CASE("phedra intersections: text, JSON and exit codes", "[self-intersection][cli]") {
  const std::string partly = data + "/partly-buildable.json";
  const Run text = phedra_cli({"intersections", partly});
  CHECK(text.code == 0);
  CHECK_THAT(text.out, Contains("intersection-free on ["));
  CHECK_THAT(text.out, Contains("folds shut and through"));
  CHECK_THAT(text.out, Contains("buildability: buildable over [") && Contains("only ("));
  const Run j = phedra_cli({"intersections", partly, "--json", "--samples", "50"});
  REQUIRE(j.code == 0);
  const nlohmann::json report = nlohmann::json::parse(j.out);
  CHECK(report["intersection_free"] == false);
  CHECK(report["upper"]["kind"] == "hinge");
  CHECK(report["free_interval"].size() == 2);
  CHECK(report["samples_per_side"] == 50);
  CHECK(report["buildability"]["buildable_interval"] == report["free_interval"]);
  CHECK(report["buildability"]["buildable"] == false);
  const Run crossing = phedra_cli({"intersections", data + "/self-intersecting.json"});
  CHECK(crossing.code == 1);
  CHECK_THAT(crossing.out, Contains("the configuration at t* intersects itself"));
  const Run bad = phedra_cli({"intersections", presets + "/grid-3x3.json", "--samples", "0"});
  CHECK(bad.code == 2);
  const Run info = phedra_cli({"info", data + "/self-intersecting.json"});
  CHECK_THAT(info.out, Contains("buildability:      not buildable") && Contains("penetrate"));
}

TEST_CASE("generate --no-self-intersection restricts every export to the free interval", "[self-intersection][cli]") {
  const fs::path dir = fs::temp_directory_path() / ("phedra-si-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const SelfIntersectionReport r = find_self_intersections(load_design(data + "/partly-buildable.json"));
  const std::string grid = data + "/partly-buildable.json";
  // FOLD frames: --count spreads over the free interval.
  const Run fold = phedra_cli({"generate", grid, "-o", (dir / "g.fold").string(), "--no-self-intersection", "--count", "3"});
  REQUIRE(fold.code == 0);
  std::ifstream in(dir / "g.fold");
  const nlohmann::json doc = nlohmann::json::parse(in);
  CHECK_THAT(fold.out, Contains("intersection-free interval ["));
  CHECK(doc["frame_phedra:t"].get<double>() == Approx(load_design(grid).assembly.t_star()));  // the key frame
  REQUIRE(doc["file_frames"].size() == 3);
  CHECK(doc["file_frames"][0]["frame_phedra:t"].get<double>() == Approx(r.free_lower));
  // glTF: the animated interval is recorded in the extras.
  const Run glb = phedra_cli({"generate", grid, "-o", (dir / "g.gltf").string(), "--no-self-intersection", "-q"});
  REQUIRE(glb.code == 0);
  std::ifstream gin(dir / "g.gltf");
  const nlohmann::json gltf = nlohmann::json::parse(gin);
  const nlohmann::json extras = gltf["asset"]["extras"]["phedra"];
  REQUIRE(extras.contains("animated_interval"));
  CHECK(extras["animated_interval"][0].get<double>() == Approx(r.free_lower));
  CHECK(extras["animated_interval"][1].get<double>() == Approx(r.free_upper));
  // A t outside it is refused, naming the option; nothing is written.
  const double outside = 0.5 * (r.free_upper + r.t_mu);
  const Run out_of = phedra_cli({"generate", grid, "-o", (dir / "x.json").string(), "--no-self-intersection", "--t",
                                 std::to_string(outside)});
  CHECK(out_of.code == 2);
  CHECK_THAT(out_of.err, Contains("--no-self-intersection: t = "));
  CHECK(!fs::exists(dir / "x.json"));
  const Run at = phedra_cli({"generate", grid, "-o", (dir / "x.obj").string(), "--no-self-intersection", "--at",
                             std::to_string(outside)});
  CHECK(at.code == 2);
  CHECK_THAT(at.err, Contains("--at: t = "));
  // Intersecting at t*: refused.
  const Run crossing = phedra_cli({"generate", data + "/self-intersecting.json", "-o", (dir / "c.glb").string(),
                                   "--no-self-intersection"});
  CHECK(crossing.code == 2);
  CHECK_THAT(crossing.err, Contains("--no-self-intersection: the configuration at t* = 1 already intersects itself"));
  CHECK(!fs::exists(dir / "c.glb"));
  // Not with --cycle.
  const Run cycle = phedra_cli({"generate", grid, "-o", (dir / "c.glb").string(), "--no-self-intersection", "--cycle"});
  CHECK(cycle.code == 2);
  fs::remove_all(dir);
}
