#include "gltf_parts.h"

#include "phedra/errors.h"

namespace phedra::gltf {

tinygltf::Value to_value(const nlohmann::json& j) {
  if (j.is_object()) {
    tinygltf::Value::Object o;
    for (const auto& [key, value] : j.items()) o[key] = to_value(value);
    return tinygltf::Value(o);
  }
  if (j.is_array()) {
    tinygltf::Value::Array a;
    for (const auto& value : j) a.push_back(to_value(value));
    return tinygltf::Value(a);
  }
  if (j.is_boolean()) return tinygltf::Value(j.get<bool>());
  if (j.is_number_integer()) return tinygltf::Value(static_cast<int>(j.get<long long>()));
  if (j.is_number()) return tinygltf::Value(j.get<double>());
  if (j.is_string()) return tinygltf::Value(j.get<std::string>());
  return tinygltf::Value();
}

void add_weights_animation(tinygltf::Model& model, const std::string& name, int times, int weights) {
  tinygltf::Animation animation;
  animation.name = name;
  tinygltf::AnimationSampler sampler;
  sampler.input = times;
  sampler.output = weights;
  sampler.interpolation = "LINEAR";
  animation.samplers.push_back(sampler);
  tinygltf::AnimationChannel channel;
  channel.sampler = 0;
  channel.target_node = 0;
  channel.target_path = "weights";
  animation.channels.push_back(channel);
  model.animations.push_back(animation);
}

float checked(double x) {
  const float f = static_cast<float>(x);
  if (!std::isfinite(f)) throw Error(ExitCode::internal, "refusing to write a non-finite number to glTF");
  return f;
}

std::string face_name(const Assembly& a, const AssemblyMesh& mesh, std::size_t f) {
  const VertexRef& r = mesh.vertices[mesh.faces[f][0]];
  const GridTopology& g = a.topology(mesh.face_member[f]);
  return a.member_name(mesh.face_member[f]) + " panel (" + std::to_string(g.row_of(r.vertex)) + "," +
         std::to_string(g.column_of(r.vertex)) + ")";
}

}  // namespace phedra::gltf
