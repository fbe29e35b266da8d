#include "phedra/oscillation_gltf.h"

#include "gltf_parts.h"

#include "phedra/errors.h"
#include "phedra/gltf_export.h"

#include <cmath>
#include <numbers>
#include <sstream>

namespace phedra {

std::string oscillation_gltf_bytes(const OscillationScene& scene, bool binary) {
  using namespace gltf;
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "phedra";
  BufferBuilder buffer(model);

  tinygltf::Material material;
  material.name = "panels";
  material.doubleSided = true;
  material.pbrMetallicRoughness.baseColorFactor = {0.55, 0.7, 0.9, 1.0};
  material.pbrMetallicRoughness.metallicFactor = 0.0;
  material.pbrMetallicRoughness.roughnessFactor = 0.8;
  model.materials.push_back(material);

  auto vec3_accessor = [&](const Points& points) {
    std::vector<float> values;
    values.reserve(3 * points.size());
    std::vector<double> lo(3, INFINITY), hi(3, -INFINITY);
    for (const Vec3& p : points) {
      const Vec3 y = to_y_up(p);
      for (int c = 0; c < 3; ++c) {
        const float f = checked(y(c));
        values.push_back(f);
        lo[c] = std::min(lo[c], static_cast<double>(f));
        hi[c] = std::max(hi[c], static_cast<double>(f));
      }
    }
    const int view = buffer.add_view(values, TINYGLTF_TARGET_ARRAY_BUFFER);
    return buffer.add_accessor(view, 0, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, points.size(), lo, hi);
  };

  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.material = 0;
  primitive.attributes["POSITION"] = vec3_accessor(scene.positions);
  std::vector<std::uint32_t> indices;
  for (const auto& t : scene.triangles) indices.insert(indices.end(), t.begin(), t.end());
  const int index_view = buffer.add_view(indices, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  primitive.indices = buffer.add_accessor(index_view, 0, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR,
                                          indices.size());
  tinygltf::Value::Array names;
  for (const OscillationField& field : scene.fields) {
    for (double sign : {1.0, -1.0}) {
      Points d = field.displacement;
      for (Vec3& v : d) v *= sign;
      primitive.targets.push_back({{"POSITION", vec3_accessor(d)}});
      names.push_back(tinygltf::Value(field.name + (sign > 0 ? " +" : " -")));
    }
  }
  tinygltf::Mesh mesh;
  mesh.name = scene.name;
  mesh.primitives.push_back(primitive);
  mesh.weights.assign(2 * scene.fields.size(), 0.0);
  tinygltf::Value::Object mesh_extras;
  mesh_extras["targetNames"] = tinygltf::Value(names);  // Blender's shape key names, three.js's morphTargetDictionary
  mesh.extras = tinygltf::Value(mesh_extras);
  model.meshes.push_back(mesh);
  tinygltf::Node node;
  node.mesh = 0;
  node.name = scene.name;
  model.nodes.push_back(node);
  tinygltf::Scene gltf_scene;
  gltf_scene.nodes.push_back(0);
  model.scenes.push_back(gltf_scene);
  model.defaultScene = 0;

  if (!scene.fields.empty()) {
    // Field k: seconds [k T, (k + 1) T], 32 steps of sin(2 pi s) split into its two targets.
    const int steps = 32;
    const std::size_t targets = 2 * scene.fields.size();
    std::vector<float> times, weights;
    for (std::size_t k = 0; k < scene.fields.size(); ++k) {
      for (int s = k == 0 ? 0 : 1; s <= steps; ++s) {
        const double phase = static_cast<double>(s) / steps;
        times.push_back(checked(scene.seconds * (static_cast<double>(k) + phase)));
        const double w = std::sin(2.0 * std::numbers::pi * phase);
        for (std::size_t j = 0; j < targets; ++j) {
          const double value = j == 2 * k ? std::max(0.0, w) : j == 2 * k + 1 ? std::max(0.0, -w) : 0.0;
          weights.push_back(checked(std::abs(value) < 1e-12 ? 0.0 : value));
        }
      }
    }
    const int time_view = buffer.add_view(times, 0);
    const int time_accessor = buffer.add_accessor(time_view, 0, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR,
                                                  times.size(), {times.front()}, {times.back()});
    const int weight_view = buffer.add_view(weights, 0);
    const int weight_accessor =
        buffer.add_accessor(weight_view, 0, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, weights.size());
    add_weights_animation(model, "modes", time_accessor, weight_accessor);
  }

  nlohmann::json phedra = scene.extras;
  phedra["up"] = "glTF (x, y, z) = preset (x, z, -y)";
  phedra["seconds_per_field"] = scene.seconds;
  tinygltf::Value::Object extras;
  extras["phedra"] = to_value(phedra);
  model.asset.extras = tinygltf::Value(extras);
  model.scenes[0].extras = tinygltf::Value(extras);
  tinygltf::TinyGLTF writer;
  std::ostringstream out;
  if (!writer.WriteGltfSceneToStream(&model, out, !binary, binary)) throw Error(ExitCode::internal, "glTF serialisation failed");
  return out.str();
}

}  // namespace phedra
