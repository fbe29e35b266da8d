// Exports: the glTF node animation (tree hinges closed between keyframes, other
// hinges within the tolerance), its structure, FOLD and OBJ/PLY.

#include "phedra/assembly_mesh.h"
#include "phedra/design.h"
#include "phedra/fold_export.h"
#include "phedra/gltf_export.h"
#include "phedra/keyframes.h"
#include "phedra/mesh_export.h"
#include "phedra/panel_tree.h"
#include "phedra/design_preset.h"
#include "phedra/fold_angle.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <filesystem>
#include <functional>
#include <sstream>

using namespace phedra;
using nlohmann::json;

namespace {

Design design(const std::string& preset) { return load_design(std::string(PHEDRA_PRESETS_DIR) + "/" + preset + ".json"); }

Points y_up_positions(const Design& d, const AssemblyMesh& mesh, double t) {
  Points p = mesh.positions(d.assembly.evaluate(t));
  for (Vec3& x : p) x = to_y_up(x);
  return p;
}

}  // namespace

TEST_CASE("panel tree: poses reproduce every configuration, tree hinges stay closed between keyframes", "[exports]") {
  for (const std::string preset : {"default", "grid-3x3", "merged-tube", "anti-parallelogram-tube"}) {
    CAPTURE(preset);
    const Design d = design(preset);
    const AssemblyMesh mesh = panel_mesh(d);
    const PanelTree tree(mesh.faces, y_up_positions(d, mesh, d.assembly.t_star()));
    const double size = d.assembly.model_size();
    const FlexionInterval& f = d.assembly.flexion_interval();
    // Local poses, composed along the tree, give back the positions.
    for (double s : {0.0, 0.3, 1.0}) {
      const double t = d.assembly.t_at_fraction(s);
      const Points v = y_up_positions(d, mesh, t);
      const std::vector<RigidPose> world = tree.world_poses(tree.local_poses(v));
      double worst = 0;
      for (std::size_t p = 0; p < tree.panels(); ++p) {
        for (int k = 0; k < 4; ++k) worst = std::max(worst, (world[p].apply(tree.local_vertices(p)[k]) - v[mesh.faces[p][k]]).norm());
      }
      CHECK(worst <= 1e-9 * size);
    }
    // Between two keyframes, a child's hinge endpoints agree in parent and child.
    const std::vector<RigidPose> a = tree.local_poses(y_up_positions(d, mesh, f.lower.t));
    const std::vector<RigidPose> b = tree.local_poses(y_up_positions(d, mesh, d.assembly.t_at_fraction(0.2)));
    for (double s : {0.25, 0.5, 0.9}) {
      const std::vector<RigidPose> world = tree.world_poses(interpolate_poses(a, b, s));
      double worst = 0;
      for (std::size_t p = 0; p < tree.panels(); ++p) {
        if (tree.parent(p) == SIZE_MAX) continue;
        const std::size_t q = tree.parent(p);
        for (int k = 0; k < 4; ++k) {
          for (int l = 0; l < 4; ++l) {
            if (mesh.faces[p][k] != mesh.faces[q][l]) continue;
            worst = std::max(worst, (world[p].apply(tree.local_vertices(p)[k]) - world[q].apply(tree.local_vertices(q)[l])).norm());
          }
        }
      }
      CHECK(worst <= 1e-9 * size);
    }
  }
}

TEST_CASE("glTF nodes: structure, keyframes within the hinge tolerance, animation extras", "[exports]") {
  for (const std::string preset : {"default", "grid-3x3", "merged-tube"}) {
    CAPTURE(preset);
    const Design d = design(preset);
    GltfOptions options;
    options.morph = false;
    GltfReport report;
    const std::string bytes = gltf_bytes(d, options, &report);
    CHECK(report.max_opening <= report.tolerance);
    CHECK(report.max_vertex_error <= report.tolerance);
    CHECK(report.keyframes >= options.keyframes.initial);
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string error, warning;
    REQUIRE(loader.LoadBinaryFromMemory(&model, &error, &warning, reinterpret_cast<const unsigned char*>(bytes.data()),
                                        static_cast<unsigned int>(bytes.size())));
    CHECK(model.nodes.size() == report.panels);
    CHECK(model.materials.size() == d.assembly.member_count());
    for (const auto& m : model.materials) CHECK(m.doubleSided);
    REQUIRE(model.animations.size() == 1);
    CHECK(model.animations[0].channels.size() >= report.panels);
    const auto& extras = model.asset.extras.Get("phedra");
    CHECK(extras.Get("keyframe_t").ArrayLen() == report.keyframes);
    CHECK(extras.Get("max_hinge_opening").GetNumberAsDouble() == report.max_opening);
    for (const auto& accessor : model.accessors) {
      if (accessor.type == TINYGLTF_TYPE_VEC3 && !accessor.minValues.empty()) CHECK(accessor.maxValues.size() == 3);
    }
    // A tighter tolerance needs more keyframes.
    GltfOptions tight = options;
    tight.keyframes.relative_tolerance = 1e-4;
    GltfReport tight_report;
    gltf_bytes(d, tight, &tight_report);
    CHECK(tight_report.keyframes > report.keyframes);
    CHECK(tight_report.max_opening <= tight_report.tolerance);
    CHECK(tight_report.max_vertex_error <= tight_report.tolerance);
  }
  // Ping-pong plays back: 2k - 1 keyframes; static: no animation.
  const Design d = design("parallelogram-tube");
  GltfOptions ping;
  ping.ping_pong = true;
  ping.binary = false;
  GltfReport r;
  const json text = json::parse(gltf_bytes(d, ping, &r));
  CHECK(text["accessors"][text["animations"][0]["samplers"][0]["input"].get<int>()]["count"] == 2 * r.keyframes - 1);
  GltfOptions still;
  still.static_t = d.assembly.t_at_fraction(0.5);
  still.binary = false;
  const json s = json::parse(gltf_bytes(d, still));
  CHECK_FALSE(s.contains("animations"));
  CHECK(s["asset"]["extras"]["phedra"]["t"] == *still.static_t);
}

TEST_CASE("FOLD: fold angle signs, frames and assignments", "[exports]") {
  // A valley: the second face rises on the normal side.
  const Vec3 up(0, 0, 1);
  const double a = 0.3;
  CHECK(fold_angle_degrees(up, Vec3(-std::sin(a), 0, std::cos(a)), Vec3(0, 0, 0), Vec3(0, 1, 0)) ==
        Approx(a * 180 / M_PI));
  CHECK(fold_angle_degrees(up, Vec3(std::sin(a), 0, std::cos(a)), Vec3(0, 0, 0), Vec3(0, 1, 0)) ==
        Approx(-a * 180 / M_PI));
  const Design d = design("merged-tube");
  const std::vector<double> ts{d.assembly.t_at_fraction(0), d.assembly.t_star(), d.assembly.t_at_fraction(1)};
  const json fold = json::parse(fold_json(d, ts));
  CHECK(fold["file_spec"] == 1.2);
  CHECK(fold["file_frames"].size() == 3);  // every given t; the key frame is t*
  CHECK(fold["frame_phedra:t"] == d.assembly.t_star());
  CHECK(fold["faces_vertices"].size() == 80);
  CHECK(fold["vertices_coords"].size() == 88);
  const std::size_t edges = fold["edges_vertices"].size();
  std::size_t boundary = 0;
  for (const auto& x : fold["edges_assignment"]) boundary += x == "B";
  CHECK(boundary == 16);  // two octagons
  for (const auto& frame : fold["file_frames"]) {
    CHECK(frame["frame_inherit"] == true);
    CHECK(frame["edges_foldAngle"].size() == edges);
    CHECK(frame["vertices_coords"].size() == 88);
  }
  // The hinges where a removed strip was are flat: the coupled cells' sides continue straight.
  std::size_t flat = 0;
  for (const auto& x : fold["edges_assignment"]) flat += x == "F";
  CHECK(flat == 2 * 2 * 10);  // two junctions, two hinge lines each, ten strips
}

TEST_CASE("FOLD of every shipped preset: key frame t*, no zero-length edge, connected, signs match", "[exports]") {
  for (const auto& entry : std::filesystem::directory_iterator(PHEDRA_PRESETS_DIR)) {
    const std::string name = entry.path().stem().string();
    if (entry.path().extension() != ".json" || name == "preset.schema") continue;
    CAPTURE(name);
    const Design d = design(name);
    std::vector<double> ts;
    for (int k = 0; k <= 20; ++k) ts.push_back(d.assembly.t_at_fraction(k / 20.0));
    const json fold = json::parse(fold_json(d, ts));
    CHECK(fold["frame_phedra:t"] == d.assembly.t_star());
    const double size = d.assembly.model_size();
    const auto& edges = fold["edges_vertices"];
    // One connected mesh (arrays: the cells share vertices).
    const std::size_t n = fold["vertices_coords"].size();
    std::vector<std::size_t> root(n);
    for (std::size_t v = 0; v < n; ++v) root[v] = v;
    std::function<std::size_t(std::size_t)> find = [&](std::size_t v) { return root[v] == v ? v : root[v] = find(root[v]); };
    for (const auto& e : edges) root[find(e[0].get<std::size_t>())] = find(e[1].get<std::size_t>());
    std::size_t components = 0;
    for (std::size_t v = 0; v < n; ++v) components += find(v) == v;
    CHECK(components == 1);
    std::vector<json> states{fold};
    for (const auto& f : fold["file_frames"]) states.push_back(f);
    std::vector<double> previous;
    for (std::size_t k = 0; k < states.size(); ++k) {
      const auto& v = states[k]["vertices_coords"];
      double shortest = INFINITY;
      for (const auto& e : edges) {
        const auto& a = v[e[0].get<std::size_t>()];
        const auto& b = v[e[1].get<std::size_t>()];
        shortest = std::min(shortest, std::hypot(a[0].get<double>() - b[0].get<double>(), a[1].get<double>() - b[1].get<double>(),
                                                 a[2].get<double>() - b[2].get<double>()));
      }
      CHECK(shortest > 1e-6 * size);
      const auto& angles = states[k]["edges_foldAngle"];
      const auto& assignment = states[k]["edges_assignment"];
      for (std::size_t e = 0; e < edges.size(); ++e) {
        const double angle = angles[e].get<double>();
        const std::string a = assignment[e].get<std::string>();
        if (a == "F" || a == "B") CHECK(angle == 0.0);
        if (a == "V") CHECK(angle > 0.0);
        if (a == "M") CHECK(angle < 0.0);
      }
    }
    // Frames in increasing t: no hinge jumps from one sign to the other at +-180.
    for (std::size_t k = 2; k < states.size(); ++k) {
      const auto& a = states[k - 1]["edges_foldAngle"];
      const auto& b = states[k]["edges_foldAngle"];
      for (std::size_t e = 0; e < edges.size(); ++e) CHECK(std::abs(a[e].get<double>() - b[e].get<double>()) < 180.0);
    }
  }
  // default.json: the two vertices its boundary column puts at one place are one, its two panels triangles.
  const json fold = json::parse(fold_json(design("default"), {design("default").assembly.t_star()}));
  std::size_t triangles = 0;
  for (const auto& f : fold["faces_vertices"]) triangles += f.size() == 3;
  CHECK(triangles == 2);
  CHECK(fold["vertices_coords"].size() == 70);
}

TEST_CASE("OBJ and PLY read back with OpenMesh", "[exports]") {
  using Mesh = OpenMesh::PolyMesh_ArrayKernelT<>;
  const Design d = design("merged-tube");
  const double t = d.assembly.t_at_fraction(0.5);
  const Points expected = merged_mesh(d.assembly).positions(d.assembly.evaluate(t));
  for (const std::string ext : {".obj", ".ply"}) {
    CAPTURE(ext);
    std::istringstream in(mesh_text(d, t, ext));
    Mesh mesh;
    OpenMesh::IO::Options options;
    REQUIRE(OpenMesh::IO::read_mesh(mesh, in, ext, options));
    CHECK(mesh.n_vertices() == 88);
    CHECK(mesh.n_faces() == 80);
    double worst = 0;
    for (auto v : mesh.vertices()) {
      const auto p = mesh.point(v);
      worst = std::max(worst, (Vec3(p[0], p[1], p[2]) - expected[v.idx()]).norm());
    }
    CHECK(worst <= 1e-6 * d.assembly.model_size());
  }
  // default.json: the two vertices its boundary column puts at one place are
  // written once; the two panels between them are triangles (still faces 0..55).
  const Design open = design("default");
  std::istringstream in(mesh_text(open, open.assembly.t_star(), ".obj"));
  Mesh mesh;
  OpenMesh::IO::Options options;
  REQUIRE(OpenMesh::IO::read_mesh(mesh, in, ".obj", options));
  CHECK(mesh.n_vertices() == 70);
  CHECK(mesh.n_faces() == 56);
  std::size_t triangles = 0;
  double shortest = INFINITY;
  for (auto f : mesh.faces()) triangles += mesh.valence(f) == 3;
  for (auto e : mesh.edges()) shortest = std::min(shortest, static_cast<double>(mesh.calc_edge_length(e)));
  CHECK(triangles == 2);
  CHECK(shortest > 1e-6 * open.assembly.model_size());
}
