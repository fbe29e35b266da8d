#include "phedra/gltf_export.h"

#include "phedra/assembly_check.h"
#include "phedra/assembly_mesh.h"
#include "phedra/errors.h"
#include "phedra/panel_tree.h"

#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <map>
#include <sstream>

namespace phedra {
namespace {

/// Appends raw values to the single buffer, 4-byte aligned; returns the bufferView index.
class BufferBuilder {
 public:
  explicit BufferBuilder(tinygltf::Model& model) : model_(model) { model_.buffers.resize(1); }

  template <class T>
  int add_view(const std::vector<T>& values, int target, std::size_t stride = 0) {
    auto& data = model_.buffers[0].data;
    while (data.size() % 4) data.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = data.size();
    view.byteLength = values.size() * sizeof(T);
    view.target = target;
    view.byteStride = stride;
    const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
    data.insert(data.end(), bytes, bytes + view.byteLength);
    model_.bufferViews.push_back(view);
    return static_cast<int>(model_.bufferViews.size()) - 1;
  }

  int add_accessor(int view, std::size_t offset, int component, int type, std::size_t count,
                   std::vector<double> min = {}, std::vector<double> max = {}) {
    tinygltf::Accessor a;
    a.bufferView = view;
    a.byteOffset = offset;
    a.componentType = component;
    a.type = type;
    a.count = count;
    a.minValues = std::move(min);
    a.maxValues = std::move(max);
    model_.accessors.push_back(a);
    return static_cast<int>(model_.accessors.size()) - 1;
  }

 private:
  tinygltf::Model& model_;
};

float checked(double x) {
  const float f = static_cast<float>(x);
  if (!std::isfinite(f)) throw Error(ExitCode::internal, "refusing to write a non-finite number to glTF");
  return f;
}

std::array<double, 3> hsv_to_rgb(double h, double s, double v) {
  const double c = v * s, x = c * (1 - std::abs(std::fmod(h * 6, 2.0) - 1)), m = v - c;
  const int sector = static_cast<int>(h * 6) % 6;
  const double table[6][3] = {{c, x, 0}, {x, c, 0}, {0, c, x}, {0, x, c}, {x, 0, c}, {c, 0, x}};
  return {table[sector][0] + m, table[sector][1] + m, table[sector][2] + m};
}

std::string face_name(const Assembly& a, const AssemblyMesh& mesh, std::size_t f) {
  const VertexRef& r = mesh.vertices[mesh.faces[f][0]];
  const GridTopology& g = a.topology(mesh.face_member[f]);
  return a.member_name(mesh.face_member[f]) + " panel (" + std::to_string(g.row_of(r.vertex)) + "," +
         std::to_string(g.column_of(r.vertex)) + ")";
}

}  // namespace

std::string gltf_bytes(const Design& design, const GltfOptions& options, GltfReport* report) {
  const Assembly& assembly = design.assembly;
  const AssemblyMesh mesh = design.merge ? merged_mesh(assembly) : separate_mesh(assembly);
  auto positions = [&](double t) {
    Points p = mesh.positions(assembly.evaluate(t));
    for (Vec3& x : p) x = to_y_up(x);
    return p;
  };
  const double rest_t = assembly.t_star();
  const Points reference = positions(rest_t);
  const PanelTree tree(mesh.faces, reference);
  const double size = assembly.model_size();

  // Copies of one place that must stay together: each mesh vertex in all its panels,
  // and the vertices members share (separate meshes keep one copy per member).
  std::map<std::size_t, std::vector<std::pair<std::size_t, int>>> by_vertex;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    for (int k = 0; k < 4; ++k) by_vertex[mesh.faces[f][k]].push_back({f, k});
  }
  std::vector<std::vector<std::pair<std::size_t, int>>> groups;
  for (auto& [v, copies] : by_vertex) {
    if (copies.size() > 1) groups.push_back(copies);
  }
  if (!design.merge) {
    std::map<std::pair<std::size_t, std::size_t>, std::size_t> mesh_vertex;
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) mesh_vertex[{mesh.vertices[v].member, mesh.vertices[v].vertex}] = v;
    for (const auto& shared : assembly.shared_vertices()) {
      std::vector<std::pair<std::size_t, int>> group;
      for (const VertexRef& r : shared) {
        const auto it = by_vertex.find(mesh_vertex.at({r.member, r.vertex}));
        if (it != by_vertex.end()) group.push_back(it->second.front());
      }
      if (group.size() > 1) groups.push_back(group);
    }
  }

  Keyframes keys;
  if (options.static_t) {
    keys.t = {*options.static_t};
    keys.local = {tree.local_poses(positions(*options.static_t))};
  } else {
    keys = choose_keyframes(tree, positions, assembly.flexion_interval().lower.t, assembly.flexion_interval().upper.t,
                            groups, size, options.keyframes, options.progress);
  }

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "phedra";
  BufferBuilder buffer(model);

  // Materials: one per member, double-sided.
  for (std::size_t m = 0; m < assembly.member_count(); ++m) {
    const auto rgb = hsv_to_rgb(std::fmod(0.58 + 0.618034 * static_cast<double>(m), 1.0), 0.55, 0.9);
    tinygltf::Material material;
    material.name = assembly.member_name(m);
    material.doubleSided = true;
    material.pbrMetallicRoughness.baseColorFactor = {rgb[0], rgb[1], rgb[2], 1.0};
    material.pbrMetallicRoughness.metallicFactor = 0.0;
    material.pbrMetallicRoughness.roughnessFactor = 0.8;
    model.materials.push_back(material);
  }

  // Geometry: one shared index accessor, one position accessor per panel (its
  // vertices relative to the node origin, at t*).
  const std::vector<std::uint16_t> indices{0, 1, 2, 0, 2, 3};
  const int index_view = buffer.add_view(indices, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  const int index_accessor =
      buffer.add_accessor(index_view, 0, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, 6, {0}, {3});
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
    primitive.indices = index_accessor;
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
  tinygltf::Value::Array keyframe_t;
  if (!options.static_t) {
    const double lo = assembly.flexion_interval().lower.t, width = assembly.flexion_interval().width();
    std::vector<std::size_t> sequence;
    for (std::size_t k = 0; k < keys.t.size(); ++k) sequence.push_back(k);
    if (options.ping_pong) {
      for (std::size_t k = keys.t.size() - 1; k-- > 0;) sequence.push_back(k);
    }
    std::vector<float> times;
    for (std::size_t s = 0; s < sequence.size(); ++s) {
      const double forward = (keys.t[sequence[s]] - lo) / width * options.seconds;
      times.push_back(checked(s < keys.t.size() ? forward : 2.0 * options.seconds - forward));
      keyframe_t.push_back(tinygltf::Value(keys.t[sequence[s]]));
    }
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
    auto add_channel = [&](std::size_t node, const char* path, int output) {
      tinygltf::AnimationSampler sampler;
      sampler.input = time_accessor;
      sampler.output = output;
      sampler.interpolation = "LINEAR";
      animation.samplers.push_back(sampler);
      tinygltf::AnimationChannel channel;
      channel.sampler = static_cast<int>(animation.samplers.size()) - 1;
      channel.target_node = static_cast<int>(node);
      channel.target_path = path;
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

  tinygltf::Value::Object phedra;
  phedra["name"] = tinygltf::Value(assembly.name());
  phedra["kind"] = tinygltf::Value(design.kind);
  phedra["t_lambda"] = tinygltf::Value(assembly.flexion_interval().lower.t);
  phedra["t_mu"] = tinygltf::Value(assembly.flexion_interval().upper.t);
  phedra["t_star"] = tinygltf::Value(assembly.t_star());
  phedra["model_size"] = tinygltf::Value(size);
  phedra["up"] = tinygltf::Value(std::string("glTF (x, y, z) = preset (x, z, -y)"));
  if (options.static_t) {
    phedra["t"] = tinygltf::Value(*options.static_t);
  } else {
    phedra["seconds"] = tinygltf::Value(options.seconds);
    phedra["ping_pong"] = tinygltf::Value(options.ping_pong);
    phedra["keyframe_t"] = tinygltf::Value(keyframe_t);
    phedra["max_hinge_opening"] = tinygltf::Value(keys.max_opening);
    phedra["hinge_tolerance"] = tinygltf::Value(keys.tolerance);
  }
  // The check figures over the interval, relative to the model size, for viewers.
  const AssemblyCheckReport check = check_assembly(assembly, {});
  tinygltf::Value::Object figures;
  figures["passed"] = tinygltf::Value(check.passed());
  figures["planarity"] = tinygltf::Value(check.planarity.value / size);
  figures["isometry"] = tinygltf::Value(check.isometry.value / size);
  figures["closure"] = tinygltf::Value(check.closure.value / size);
  figures["shared_vertices"] = tinygltf::Value(check.shared.value / size);
  figures["samples"] = tinygltf::Value(static_cast<int>(check.samples));
  phedra["check"] = tinygltf::Value(figures);
  tinygltf::Value::Object extras;
  extras["phedra"] = tinygltf::Value(phedra);
  model.asset.extras = tinygltf::Value(extras);

  tinygltf::TinyGLTF writer;
  std::ostringstream out;
  if (!writer.WriteGltfSceneToStream(&model, out, !options.binary, options.binary)) {
    throw Error(ExitCode::internal, "glTF serialisation failed");
  }
  std::string bytes = out.str();
  if (report) {
    report->panels = tree.panels();
    report->keyframes = keys.t.size();
    report->max_opening = keys.max_opening;
    report->opening_t = keys.opening_t;
    report->tolerance = keys.tolerance;
    report->model_size = size;
    report->bytes = bytes.size();
  }
  return bytes;
}

}  // namespace phedra
