#include "gltf_parts.h"

#include "phedra/errors.h"
#include "phedra/keyframes.h"
#include "phedra/panel_tree.h"

#include <algorithm>
#include <map>

namespace phedra::gltf {

void build_nodes(tinygltf::Model& model, BufferBuilder& buffer, const Design& design, const AssemblyMesh& mesh,
                 const MotionPath& path, const GltfOptions& options, GltfReport& report,
                 tinygltf::Value::Array& keyframe_t) {
  const Assembly& assembly = design.assembly;
  const Points reference = path.positions(path.rest);
  const PanelTree tree(mesh.faces, reference);
  const double size = assembly.model_size();

  // Copies of one place that must stay together: each mesh vertex in all its
  // panels (the mesh welds the vertices members share).
  std::map<std::size_t, std::vector<std::pair<std::size_t, int>>> by_vertex;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    for (int k = 0; k < 4; ++k) by_vertex[mesh.faces[f][k]].push_back({f, k});
  }
  std::vector<std::vector<std::pair<std::size_t, int>>> groups;
  for (auto& [v, copies] : by_vertex) {
    if (copies.size() > 1) groups.push_back(copies);
  }

  Keyframes keys;
  if (options.static_t) {
    keys.t = {*options.static_t};
    keys.local = {tree.local_poses(path.positions_at_t(*options.static_t))};
  } else {
    KeyframeOptions keyframes = options.keyframes;
    keyframes.initial = std::max(keyframes.initial, path.minimum_keyframes);
    keys = choose_keyframes(tree, path.positions, path.lo, path.hi, groups, size, keyframes, options.progress);
  }

  // Geometry: one shared index accessor, one position accessor per panel (its
  // vertices relative to the node origin, at t*).
  const std::vector<std::uint16_t> indices{0, 1, 2, 0, 2, 3};
  const int index_view = buffer.add_view(indices, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  const int index_accessor =
      buffer.add_accessor(index_view, 0, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, 6, {0}, {3});
  // A panel with two coincident corners (welded: one mesh vertex) is the triangle it is.
  std::map<std::vector<std::uint16_t>, int> triangle_accessors;
  std::vector<float> vertex_data;
  vertex_data.reserve(tree.panels() * 12);
  for (std::size_t f = 0; f < tree.panels(); ++f) {
    for (const Vec3& v : tree.local_vertices(f)) {
      for (int c = 0; c < 3; ++c) vertex_data.push_back(checked(v[c]));
    }
  }
  const int vertex_view = buffer.add_view(vertex_data, TINYGLTF_TARGET_ARRAY_BUFFER, 12);
  const std::vector<RigidPose> rest = tree.local_poses(reference);
  const std::vector<RigidPose>& shown = options.static_t ? keys.local.front() : rest;
  for (std::size_t f = 0; f < tree.panels(); ++f) {
    std::vector<double> lo(3, INFINITY), hi(3, -INFINITY);
    for (int k = 0; k < 4; ++k) {
      for (int c = 0; c < 3; ++c) {
        lo[c] = std::min(lo[c], static_cast<double>(vertex_data[f * 12 + k * 3 + c]));
        hi[c] = std::max(hi[c], static_cast<double>(vertex_data[f * 12 + k * 3 + c]));
      }
    }
    tinygltf::Primitive primitive;
    primitive.attributes["POSITION"] = buffer.add_accessor(vertex_view, f * 48, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                                           TINYGLTF_TYPE_VEC3, 4, lo, hi);
    std::vector<std::uint32_t> corners;
    append_triangles(mesh.faces[f], corners);
    if (corners.size() == 6) {
      primitive.indices = index_accessor;
    } else {
      std::vector<std::uint16_t> local;
      for (std::uint32_t c : corners) {
        local.push_back(static_cast<std::uint16_t>(std::find(mesh.faces[f].begin(), mesh.faces[f].end(), c) - mesh.faces[f].begin()));
      }
      auto [it, added] = triangle_accessors.try_emplace(local, 0);
      if (added) {
        it->second = buffer.add_accessor(buffer.add_view(local, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER), 0,
                                         TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, local.size(),
                                         {static_cast<double>(*std::min_element(local.begin(), local.end()))},
                                         {static_cast<double>(*std::max_element(local.begin(), local.end()))});
      }
      primitive.indices = it->second;
    }
    primitive.material = static_cast<int>(mesh.face_member[f]);
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    tinygltf::Mesh m;
    m.name = face_name(assembly, mesh, f);
    m.primitives.push_back(primitive);
    model.meshes.push_back(m);

    tinygltf::Node node;
    node.name = m.name;
    node.mesh = static_cast<int>(f);
    const RigidPose& pose = shown[f];
    node.rotation = {pose.rotation.x(), pose.rotation.y(), pose.rotation.z(), pose.rotation.w()};
    node.translation = {pose.translation.x(), pose.translation.y(), pose.translation.z()};
    for (std::size_t child : tree.children(f)) node.children.push_back(static_cast<int>(child));
    tinygltf::Value::Array vertex_ids;
    for (std::size_t v : mesh.faces[f]) vertex_ids.push_back(tinygltf::Value(static_cast<int>(v)));
    tinygltf::Value::Object extras;
    extras["member"] = tinygltf::Value(static_cast<int>(mesh.face_member[f]));
    extras["face"] = tinygltf::Value(static_cast<int>(f));
    extras["vertices"] = tinygltf::Value(vertex_ids);
    node.extras = tinygltf::Value(extras);
    model.nodes.push_back(node);
  }
  tinygltf::Scene scene;
  scene.name = assembly.name();
  for (std::size_t root : tree.roots()) scene.nodes.push_back(static_cast<int>(root));
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  // Animation: keyframe times, per node rotations, per root translations.
  if (!options.static_t) {
    std::vector<double> forward_seconds;
    for (double u : keys.t) forward_seconds.push_back(path.seconds_of(u));
    const std::vector<std::size_t> sequence = play_sequence(keys.t.size(), options.ping_pong);
    const std::vector<float> times = sequence_times(forward_seconds, sequence);
    for (std::size_t k : sequence) keyframe_t.push_back(tinygltf::Value(path.t_of(keys.t[k])));
    const int time_view = buffer.add_view(times, 0);
    const int time_accessor = buffer.add_accessor(time_view, 0, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR,
                                                  times.size(), {times.front()}, {times.back()});
    std::vector<float> rotations, translations;
    rotations.reserve(tree.panels() * sequence.size() * 4);
    for (std::size_t f = 0; f < tree.panels(); ++f) {
      for (std::size_t k : sequence) {
        const Eigen::Quaterniond& q = keys.local[k][f].rotation;
        for (double c : {q.x(), q.y(), q.z(), q.w()}) rotations.push_back(checked(c));
      }
    }
    for (std::size_t root : tree.roots()) {
      for (std::size_t k : sequence) {
        for (int c = 0; c < 3; ++c) translations.push_back(checked(keys.local[k][root].translation[c]));
      }
    }
    const int rotation_view = buffer.add_view(rotations, 0);
    const int translation_view = buffer.add_view(translations, 0);
    tinygltf::Animation animation;
    animation.name = "fold";
    auto add_channel = [&](std::size_t node, const char* target, int output) {
      tinygltf::AnimationSampler sampler;
      sampler.input = time_accessor;
      sampler.output = output;
      sampler.interpolation = "LINEAR";
      animation.samplers.push_back(sampler);
      tinygltf::AnimationChannel channel;
      channel.sampler = static_cast<int>(animation.samplers.size()) - 1;
      channel.target_node = static_cast<int>(node);
      channel.target_path = target;
      animation.channels.push_back(channel);
    };
    for (std::size_t f = 0; f < tree.panels(); ++f) {
      add_channel(f, "rotation",
                  buffer.add_accessor(rotation_view, f * sequence.size() * 16, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                      TINYGLTF_TYPE_VEC4, sequence.size()));
    }
    for (std::size_t r = 0; r < tree.roots().size(); ++r) {
      add_channel(tree.roots()[r], "translation",
                  buffer.add_accessor(translation_view, r * sequence.size() * 12, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                      TINYGLTF_TYPE_VEC3, sequence.size()));
    }
    model.animations.push_back(animation);
  }

  report.panels = tree.panels();
  report.keyframes = keys.t.size();
  report.max_opening = keys.max_opening;
  report.max_vertex_error = keys.max_vertex_error;
  report.vertex_error_t = keys.vertex_error_t;
  report.narrow_vertex_error = keys.narrow_vertex_error;
  if (!options.static_t) report.narrow_seconds = keys.narrow_width / (path.hi - path.lo) * path.seconds_of(path.hi);
  report.tree_depth = tree.depth();
}

}  // namespace phedra::gltf
