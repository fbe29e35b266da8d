// The animated glTF plays the exact motion: posed by an independent player
// (support/gltf_player.h) at many times between keyframes, in both
// representations, every vertex stays within the tolerance of the design
// evaluated at the same t; and the file says what it holds where clients read it.

#include "phedra/assembly_mesh.h"
#include "phedra/design.h"
#include "phedra/gltf_export.h"
#include "phedra/panel_tree.h"
#include "support/gltf_player.h"
#include "support/random_input.h"
#include "phedra/design_preset.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>

using namespace phedra;
using phedra::test::GltfPlayer;

namespace {

Design design(const std::string& preset) { return load_design(std::string(PHEDRA_PRESETS_DIR) + "/" + preset + ".json"); }

struct Deviation {
  double worst = 0.0;  ///< absolute
  double t = 0.0;
  std::size_t vertices = 0;  ///< compared at each time
};

/// Plays the file at `times` evenly spread times over its duration, the middles
/// of `times` equal steps, and at times that approach each end geometrically
/// (next to a flexion limit the motion moves as the square root of the distance
/// to it), and compares with the design at the t the file's time map gives.
Deviation deviation_from_design(const Design& d, const std::string& bytes, std::size_t times) {
  const GltfPlayer player(bytes);
  const TimeMap map = player.time_map();
  const AssemblyMesh mesh = panel_mesh(d);
  const double duration = player.duration();
  std::vector<double> at;
  for (std::size_t k = 0; k < times; ++k) at.push_back(duration * (static_cast<double>(k) + 0.5) / static_cast<double>(times));
  for (double f = 1e-2; f > 1e-7; f /= 7.0) at.insert(at.end(), {f * duration, (1.0 - f) * duration});
  Deviation out;
  for (double seconds : at) {
    const double t = map.t_at(seconds);
    const Points exact = mesh.positions(d.assembly.evaluate(t));
    const std::vector<Vec3> shown = player.vertices_at(seconds, exact.size());
    out.vertices = 0;
    for (std::size_t v = 0; v < exact.size(); ++v) {
      if (std::isnan(shown[v].x())) continue;  // node layout: a welded duplicate no panel uses
      ++out.vertices;
      const double e = (shown[v] - to_y_up(exact[v])).norm();
      if (e > out.worst) out.worst = e, out.t = t;
    }
  }
  return out;
}

}  // namespace

TEST_CASE("glTF plays the exact motion between keyframes within the tolerance, both representations", "[exports]") {
  for (const std::string preset : {"default", "grid-3x3", "merged-tube", "helix-tube", "parallelogram-tube"}) {
    const Design d = design(preset);
    const double size = d.assembly.model_size();
    for (const bool morph : {true, false}) {
      CAPTURE(preset, morph);
      GltfOptions options;
      options.morph = morph;
      GltfReport report;
      const std::string bytes = gltf_bytes(d, options, &report);
      CHECK(report.max_vertex_error <= report.tolerance);
      // 997 times: nearly all between keyframes, none aligned with the 1/16 grid the exporter measures on.
      const Deviation played = deviation_from_design(d, bytes, 997);
      CHECK(played.vertices >= report.panels / 2);
      // float32 storage adds a few 1e-7 of the model size.
      CHECK(played.worst <= report.tolerance + 2e-6 * size);
      // The reported figure is measured at 15 points of every interval: between them a little more.
      CHECK(played.worst <= 1.01 * report.max_vertex_error + 2e-6 * size);
      // Eased at the flexion limits, no keyframe interval is left above the tolerance there.
      CHECK(report.narrow_vertex_error == 0.0);
      CHECK(report.narrow_seconds == 0.0);
    }
  }
}

TEST_CASE("glTF on random designs: the played motion within the tolerance", "[exports][random]") {
  std::mt19937_64 rng(1507);
  int exported = 0, redrawn = 0;
  for (int k = 0; k < 12; ++k) {
    test::RandomInputShape shape;
    shape.strips = 3 + k % 4;
    shape.profile_vertices = 2 + k % 3;
    shape.smooth = k % 2 == 0;
    std::optional<PHedron> p = test::draw_phedron([&] { return test::random_input(rng, shape); }, redrawn);
    if (!p) continue;
    std::optional<Design> d;
    d.emplace(Design{Assembly(std::move(*p), "random"), false, "open P-hedron"});
    ++exported;
    for (const bool morph : {true, false}) {
      CAPTURE(k, morph);
      GltfOptions options;
      options.morph = morph;
      GltfReport report;
      const std::string bytes = gltf_bytes(*d, options, &report);
      const Deviation played = deviation_from_design(*d, bytes, 301);
      CAPTURE(played.t, d->assembly.flexion_interval().lower.t, d->assembly.flexion_interval().upper.t, report.keyframes);
      CHECK(report.narrow_vertex_error == 0.0);
      CHECK(played.worst <= std::max(report.tolerance, report.max_vertex_error) + 2e-6 * d->assembly.model_size());
    }
  }
  CHECK(exported >= 8);
}

TEST_CASE("time map: linear in t but at the flexion limits, where t moves as the square of time", "[exports]") {
  // The eased fraction: 0 and 1 at the ends, continuous with a continuous slope, its inverse exact.
  for (const auto& [e0, e1] : std::vector<std::pair<double, double>>{{0, 0}, {0.0625, 0.0625}, {0.1, 0}, {0, 0.3}, {0.5, 0.5}}) {
    CAPTURE(e0, e1);
    CHECK(eased_fraction(0.0, e0, e1) == 0.0);
    CHECK(eased_fraction(1.0, e0, e1) == Approx(1.0).epsilon(1e-15));
    const double h = 1e-7;
    for (double phi = 0.001; phi < 1.0; phi += 0.0123) {
      CHECK(eased_time_fraction(eased_fraction(phi, e0, e1), e0, e1) == Approx(phi).epsilon(1e-9));
      const double left = (eased_fraction(phi, e0, e1) - eased_fraction(phi - h, e0, e1)) / h;
      const double right = (eased_fraction(phi + h, e0, e1) - eased_fraction(phi, e0, e1)) / h;
      CHECK(left == Approx(right).epsilon(1e-4).margin(1e-5));
      CHECK(right > 0.0);
    }
    // Quadratic at an eased end: a quarter of the time, a sixteenth of the distance.
    if (e0 > 0) CHECK(eased_fraction(e0 / 4, e0, e1) == Approx(eased_fraction(e0, e0, e1) / 16));
  }
  CHECK(eased_fraction(0.3, 0, 0) == Approx(0.3));

  // The exporter eases the ends that are flexion limits only, and says so in the file.
  const Design d = design("default");
  const FlexionInterval& f = d.assembly.flexion_interval();
  GltfOptions options;
  const TimeMap whole = GltfPlayer(gltf_bytes(d, options)).time_map();
  REQUIRE(whole.segments.size() == 1);
  CHECK(whole.segments[0].ease0 == Approx(options.seconds / 16));
  CHECK(whole.segments[0].ease1 == Approx(options.seconds / 16));
  CHECK(whole.t_at(0.0) == f.lower.t);
  CHECK(whole.t_at(options.seconds) == f.upper.t);
  CHECK(whole.t_at(0.5 * options.seconds) == Approx(0.5 * (f.lower.t + f.upper.t)));
  GltfOptions part = options;
  part.range = std::pair{f.lower.t, d.assembly.t_star()};
  const TimeMap half = GltfPlayer(gltf_bytes(d, part)).time_map();
  CHECK(half.segments[0].ease0 > 0.0);
  CHECK(half.segments[0].ease1 == 0.0);
  // Ping-pong: time 2T - s shows what s shows.
  GltfOptions ping = options;
  ping.ping_pong = true;
  const TimeMap back = GltfPlayer(gltf_bytes(d, ping)).time_map();
  CHECK(back.ping_pong);
  CHECK(back.t_at(2 * options.seconds - 0.1) == back.t_at(0.1));

  // Time linear in t throughout (--ease 0): the intervals touching a limit cannot
  // follow the square-root motion at any spacing clients keep; reported apart.
  GltfOptions linear = options;
  linear.ease = 0.0;
  GltfReport report;
  const TimeMap straight = GltfPlayer(gltf_bytes(d, linear, &report)).time_map();
  CHECK(straight.segments[0].ease0 == 0.0);
  CHECK(straight.t_at(1.0) == Approx(f.lower.t + 0.25 * f.width()));
  CHECK(report.narrow_vertex_error > report.tolerance);
  CHECK(report.narrow_seconds > 0.0);
}

TEST_CASE("glTF morph targets: named by t, ping-pong plays back, static at --at, metadata on the scene", "[exports]") {
  const Design d = design("parallelogram-tube");
  GltfOptions options;
  options.binary = false;
  GltfReport report;
  const GltfPlayer player(gltf_bytes(d, options, &report));
  const tinygltf::Model& m = player.model();
  REQUIRE(m.nodes.size() == 1);
  REQUIRE(m.meshes.size() == 1);
  const tinygltf::Value& names = m.meshes[0].extras.Get("targetNames");
  REQUIRE(names.IsArray());
  CHECK(names.ArrayLen() == report.keyframes);
  CHECK(names.Get(0).Get<std::string>().rfind("t=", 0) == 0);
  CHECK(m.meshes[0].primitives[0].targets.size() == report.keyframes);
  // Blender keeps the scene's extras as custom properties; asset.extras too for three.js.
  CHECK(m.scenes[0].extras.Get("phedra").Get("representation").Get<std::string>() == "morph targets");
  CHECK(m.scenes[0].extras.Get("phedra").Get("panels").GetNumberAsInt() == static_cast<int>(report.panels));
  CHECK(player.extras().Get("keyframe_t").ArrayLen() == report.keyframes);

  // Ping-pong: forward then back, 2k - 1 keyframes, and the pose at time T and 2D - T agree.
  GltfOptions ping = options;
  ping.ping_pong = true;
  GltfReport ping_report;
  const GltfPlayer back(gltf_bytes(d, ping, &ping_report));
  CHECK(back.extras().Get("keyframe_t").ArrayLen() == 2 * ping_report.keyframes - 1);
  CHECK(back.duration() == Approx(2 * options.seconds));
  const std::size_t n = panel_mesh(d).vertices.size();
  for (double s : {0.3, 1.7, 3.9}) {
    const std::vector<Vec3> going = back.vertices_at(s, n), coming = back.vertices_at(2 * options.seconds - s, n);
    for (std::size_t v = 0; v < n; ++v) CHECK((going[v] - coming[v]).norm() <= 1e-6 * d.assembly.model_size());
  }

  // Static: the mesh at t, no targets, no animation, still one mesh.
  GltfOptions still = options;
  still.static_t = d.assembly.t_at_fraction(0.25);
  const GltfPlayer at(gltf_bytes(d, still));
  CHECK(at.model().animations.empty());
  CHECK(at.model().nodes.size() == 1);
  CHECK(at.model().meshes[0].primitives[0].targets.empty());
  const Points exact = panel_mesh(d).positions(d.assembly.evaluate(*still.static_t));
  const std::vector<Vec3> shown = at.vertices_at(0.0, exact.size());
  for (std::size_t v = 0; v < exact.size(); ++v) CHECK((shown[v] - to_y_up(exact[v])).norm() <= 1e-6 * d.assembly.model_size());
}

TEST_CASE("glTF nodes: the hinge tree is rooted in the middle (the shallowest tree)", "[exports]") {
  for (const std::string preset : {"default", "grid-3x3", "merged-tube", "helix-tube", "edge-sharing-pair"}) {
    CAPTURE(preset);
    const Design d = design(preset);
    AssemblyMesh mesh = panel_mesh(d);
    mesh.faces = welded_faces(mesh, coincident_vertices(mesh, d.assembly));
    const PanelTree tree(mesh.faces, mesh.positions(d.assembly.evaluate(d.assembly.t_star())));
    // Brute force: the smallest eccentricity of any face in the hinge graph (one component here).
    std::map<std::pair<std::size_t, std::size_t>, std::vector<std::size_t>> edges;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      for (int e = 0; e < 4; ++e) {
        const std::size_t a = mesh.faces[f][e], b = mesh.faces[f][(e + 1) % 4];
        if (a != b) edges[{std::min(a, b), std::max(a, b)}].push_back(f);
      }
    }
    std::vector<std::vector<std::size_t>> next(mesh.faces.size());
    for (const auto& [edge, faces] : edges) {
      for (std::size_t x : faces) {
        for (std::size_t y : faces) {
          if (x != y) next[x].push_back(y);
        }
      }
    }
    std::size_t smallest = SIZE_MAX;
    for (std::size_t root = 0; root < mesh.faces.size(); ++root) {
      std::vector<std::size_t> depth(mesh.faces.size(), SIZE_MAX), queue{root};
      depth[root] = 0;
      for (std::size_t i = 0; i < queue.size(); ++i) {
        for (std::size_t g : next[queue[i]]) {
          if (depth[g] == SIZE_MAX) depth[g] = depth[queue[i]] + 1, queue.push_back(g);
        }
      }
      smallest = std::min(smallest, *std::max_element(depth.begin(), depth.end()));
    }
    REQUIRE(tree.roots().size() == 1);
    CHECK(tree.depth() == smallest + 1);
    GltfOptions options;
    options.morph = false;
    GltfReport report;
    const GltfPlayer player(gltf_bytes(d, options, &report));
    CHECK(report.tree_depth == tree.depth());
    CHECK(player.extras().Get("tree_depth").GetNumberAsInt() == static_cast<int>(report.tree_depth));
  }
}

TEST_CASE("glTF: coincident vertices are welded, a panel with two corners at one place is one triangle", "[exports]") {
  // default.json's boundary column: labels (0,0) and (1,0) coincide at every t.
  const Design d = design("default");
  const AssemblyMesh mesh = panel_mesh(d);
  const std::vector<std::size_t> rep = coincident_vertices(mesh, d.assembly);
  std::size_t welded = 0;
  for (std::size_t v = 0; v < rep.size(); ++v) welded += rep[v] != v;
  CHECK(welded == 2);
  const double size = d.assembly.model_size();
  for (double s : {0.0, 0.5, 1.0}) {
    const Points p = mesh.positions(d.assembly.evaluate(d.assembly.t_at_fraction(s)));
    for (std::size_t v = 0; v < rep.size(); ++v) CHECK((p[v] - p[rep[v]]).norm() <= 1e-9 * size);
  }
  std::size_t triangles = 0;
  for (const Quad& q : welded_faces(mesh, rep)) triangles += distinct_corners(q).size() == 3;
  CHECK(triangles == 2);
  // No triangle of the exported mesh has an edge shorter than 1e-9 of the model size.
  GltfOptions options;
  options.static_t = d.assembly.t_star();
  const GltfPlayer player(gltf_bytes(d, options));
  const tinygltf::Model& m = player.model();
  const std::vector<Vec3> v = player.vertices_at(0.0, mesh.vertices.size());
  const tinygltf::Accessor& ia = m.accessors[m.meshes[0].primitives[0].indices];
  const tinygltf::BufferView& view = m.bufferViews[ia.bufferView];
  const auto* idx = reinterpret_cast<const std::uint32_t*>(m.buffers[0].data.data() + view.byteOffset + ia.byteOffset);
  double shortest = INFINITY;
  for (std::size_t k = 0; k < ia.count; k += 3) {
    for (int e = 0; e < 3; ++e) shortest = std::min(shortest, (v[idx[k + e]] - v[idx[k + (e + 1) % 3]]).norm());
  }
  CHECK(shortest > 1e-9 * size);
}
