#include "support/gltf_player.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace phedra::test {

GltfPlayer::GltfPlayer(const std::string& bytes) {
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const bool binary = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
  const bool ok = binary ? loader.LoadBinaryFromMemory(&model_, &error, &warning, data, static_cast<unsigned>(bytes.size()))
                         : loader.LoadASCIIFromString(&model_, &error, &warning, bytes.c_str(),
                                                      static_cast<unsigned>(bytes.size()), "");
  if (!ok) throw std::runtime_error("tinygltf: " + error);
  for (const tinygltf::Animation& a : model_.animations) {
    for (const tinygltf::AnimationChannel& c : a.channels) {
      const tinygltf::AnimationSampler& s = a.samplers[c.sampler];
      if (s.interpolation != "LINEAR") throw std::runtime_error("only LINEAR samplers are played");
      tracks_[{c.target_node, c.target_path}] = {floats(s.input), floats(s.output)};
    }
  }
}

std::vector<float> GltfPlayer::floats(int index) const {
  const tinygltf::Accessor& a = model_.accessors[index];
  if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) throw std::runtime_error("float accessors only");
  const std::size_t width = tinygltf::GetNumComponentsInType(a.type);
  std::vector<float> out(a.count * width, 0.0f);
  if (a.bufferView >= 0) {
    const tinygltf::BufferView& v = model_.bufferViews[a.bufferView];
    const std::size_t stride = v.byteStride ? v.byteStride : width * sizeof(float);
    const unsigned char* base = model_.buffers[v.buffer].data.data() + v.byteOffset + a.byteOffset;
    for (std::size_t k = 0; k < a.count; ++k) std::memcpy(&out[k * width], base + k * stride, width * sizeof(float));
  }
  if (a.sparse.isSparse) {
    const tinygltf::BufferView& iv = model_.bufferViews[a.sparse.indices.bufferView];
    const tinygltf::BufferView& vv = model_.bufferViews[a.sparse.values.bufferView];
    const unsigned char* indices = model_.buffers[iv.buffer].data.data() + iv.byteOffset + a.sparse.indices.byteOffset;
    const unsigned char* values = model_.buffers[vv.buffer].data.data() + vv.byteOffset + a.sparse.values.byteOffset;
    for (int k = 0; k < a.sparse.count; ++k) {
      std::uint32_t i = 0;
      if (a.sparse.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) throw std::runtime_error("uint32 sparse indices only");
      std::memcpy(&i, indices + 4 * k, 4);
      std::memcpy(&out[i * width], values + k * width * sizeof(float), width * sizeof(float));
    }
  }
  return out;
}

TimeMap GltfPlayer::time_map() const {
  const tinygltf::Value& map = extras().Get("time_map");
  if (!map.IsObject()) throw std::runtime_error("the file has no extras.phedra.time_map");
  TimeMap out;
  out.ping_pong = map.Get("ping_pong").Get<bool>();
  const tinygltf::Value& segments = map.Get("segments");
  for (std::size_t k = 0; k < segments.ArrayLen(); ++k) {
    const tinygltf::Value& s = segments.Get(static_cast<int>(k));
    auto at = [&](const char* key, int i) { return s.Get(key).Get(i).GetNumberAsDouble(); };
    out.segments.push_back({at("seconds", 0), at("seconds", 1), at("t", 0), at("t", 1), at("ease_seconds", 0),
                            at("ease_seconds", 1)});
  }
  return out;
}

double GltfPlayer::duration() const {
  double d = 0.0;
  for (const auto& [key, track] : tracks_) d = std::max(d, static_cast<double>(track.times.back()));
  return d;
}

std::vector<float> GltfPlayer::sample(const Track& track, std::size_t width, double seconds, bool rotation) {
  const auto& times = track.times;
  std::size_t k = 0;
  while (k + 2 < times.size() && seconds > times[k + 1]) ++k;
  const double span = times.size() > 1 ? times[k + 1] - times[k] : 1.0;
  const double s = times.size() > 1 ? std::clamp((seconds - times[k]) / span, 0.0, 1.0) : 0.0;
  const std::size_t next = times.size() > 1 ? k + 1 : k;
  std::vector<float> out(width);
  if (rotation) {
    const float* a = &track.values[4 * k];
    const float* b = &track.values[4 * next];
    const Eigen::Quaterniond qa(a[3], a[0], a[1], a[2]), qb(b[3], b[0], b[1], b[2]);
    const Eigen::Quaterniond q = qa.slerp(s, qb);
    out = {static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z()), static_cast<float>(q.w())};
    return out;
  }
  for (std::size_t c = 0; c < width; ++c) {
    out[c] = static_cast<float>((1 - s) * track.values[width * k + c] + s * track.values[width * next + c]);
  }
  return out;
}

std::vector<Vec3> GltfPlayer::vertices_at(double seconds, std::size_t vertex_count) const {
  std::vector<Vec3> out(vertex_count, Vec3::Constant(std::numeric_limits<double>::quiet_NaN()));
  // World transforms, parents first.
  std::vector<Eigen::Affine3d> world(model_.nodes.size(), Eigen::Affine3d::Identity());
  std::vector<std::pair<int, Eigen::Affine3d>> stack;
  for (int root : model_.scenes[0].nodes) stack.push_back({root, Eigen::Affine3d::Identity()});
  while (!stack.empty()) {
    const auto [n, parent] = stack.back();
    stack.pop_back();
    const tinygltf::Node& node = model_.nodes[n];
    std::vector<double> r = node.rotation, t = node.translation;
    if (auto it = tracks_.find({n, "rotation"}); it != tracks_.end()) {
      const auto q = sample(it->second, 4, seconds, true);
      r.assign(q.begin(), q.end());
    }
    if (auto it = tracks_.find({n, "translation"}); it != tracks_.end()) {
      const auto v = sample(it->second, 3, seconds, false);
      t.assign(v.begin(), v.end());
    }
    Eigen::Affine3d local = Eigen::Affine3d::Identity();
    if (t.size() == 3) local.translate(Eigen::Vector3d(t[0], t[1], t[2]));
    if (r.size() == 4) local.rotate(Eigen::Quaterniond(r[3], r[0], r[1], r[2]).normalized());
    world[n] = parent * local;
    for (int child : node.children) stack.push_back({child, world[n]});
  }
  for (std::size_t n = 0; n < model_.nodes.size(); ++n) {
    const tinygltf::Node& node = model_.nodes[n];
    if (node.mesh < 0) continue;
    const tinygltf::Primitive& p = model_.meshes[node.mesh].primitives.front();
    const std::vector<float> base = floats(p.attributes.at("POSITION"));
    std::vector<double> position(base.begin(), base.end());
    if (!p.targets.empty()) {
      std::vector<float> weights(p.targets.size(), 0.0f);
      if (auto it = tracks_.find({static_cast<int>(n), "weights"}); it != tracks_.end()) {
        weights = sample(it->second, p.targets.size(), seconds, false);
      }
      for (std::size_t j = 0; j < p.targets.size(); ++j) {
        if (weights[j] == 0.0f) continue;
        const std::vector<float> delta = floats(p.targets[j].at("POSITION"));
        for (std::size_t c = 0; c < position.size(); ++c) position[c] += weights[j] * delta[c];
      }
    }
    const std::size_t count = position.size() / 3;
    std::vector<std::size_t> ids(count);
    for (std::size_t c = 0; c < count; ++c) ids[c] = c;
    if (node.extras.Has("vertices")) {
      for (std::size_t c = 0; c < count; ++c) ids[c] = static_cast<std::size_t>(node.extras.Get("vertices").Get(static_cast<int>(c)).GetNumberAsInt());
    }
    for (std::size_t c = 0; c < count && ids[c] < vertex_count; ++c) {
      out[ids[c]] = world[n] * Vec3(position[3 * c], position[3 * c + 1], position[3 * c + 2]);
    }
  }
  return out;
}

}  // namespace phedra::test
