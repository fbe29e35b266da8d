#include "gltf_parts.h"

#include "phedra/errors.h"
#include "phedra/interval_check.h"

#include <algorithm>
#include <sstream>
#ifndef __EMSCRIPTEN__
#include <thread>
#endif

namespace phedra::gltf {
namespace {

/// The largest distance, at the fractions `at` of [a, b], of the vertices as
/// linear interpolation between the keyframes places them from their exact
/// places at the same u; `where` gets the u. `keep` (if any) gets the positions at 1/2.
double chord_error(const std::function<Points(double)>& positions, double a, const Points& pa, double b,
                   const Points& pb, std::initializer_list<double> at, double& where, Points* keep = nullptr) {
  double error = 0.0;
  for (double s : at) {
    const double t = a + s * (b - a);
    Points truth = positions(t);
    for (std::size_t v = 0; v < truth.size(); ++v) {
      const double d = ((1 - s) * pa[v] + s * pb[v] - truth[v]).norm();
      if (d > error) error = d, where = t;
    }
    if (keep && s == 0.5) *keep = std::move(truth);
  }
  return error;
}

/// Calls work(i) for i in [0, n), on two threads for large models (not in
/// WebAssembly, built without threads); `work` must be safe to run concurrently.
void for_each_index(std::size_t n, bool large, const std::function<void(std::size_t)>& work) {
#ifndef __EMSCRIPTEN__
  if (large && n > 1) {
    std::exception_ptr failure;
    std::thread second([&] {
      try {
        for (std::size_t i = 1; i < n; i += 2) work(i);
      } catch (...) {
        failure = std::current_exception();
      }
    });
    try {
      for (std::size_t i = 0; i < n; i += 2) work(i);
    } catch (...) {
      second.join();
      throw;
    }
    second.join();
    if (failure) std::rethrow_exception(failure);
    return;
  }
#endif
  for (std::size_t i = 0; i < n; ++i) work(i);
}

/// Names of the morph targets, "t=..." with as few digits as keep them apart
/// (Blender names its shape keys after them).
tinygltf::Value target_names(const std::vector<double>& ts) {
  for (int digits = 6;; ++digits) {
    std::vector<std::string> names;
    for (double t : ts) {
      std::ostringstream name;
      name.precision(digits);
      name << "t=" << t;
      names.push_back(name.str());
    }
    std::vector<std::string> sorted = names;
    std::sort(sorted.begin(), sorted.end());
    if (digits >= 17 || std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end()) {
      tinygltf::Value::Array out;
      for (const std::string& n : names) out.push_back(tinygltf::Value(n));
      return tinygltf::Value(out);
    }
  }
}

}  // namespace

std::map<double, Points> morph_keyframes(const std::function<Points(double)>& positions, double lo, double hi,
                                          double tolerance, std::size_t initial, std::size_t maximum,
                                          double minimum_spacing, bool large, MorphErrors& errors,
                                          const KeyframeProgress& progress) {
  std::map<double, Points> frames;
  const std::vector<double> start = interval_samples(lo, hi, std::min(initial, maximum));
  std::vector<Points> first(start.size());
  for_each_index(start.size(), large, [&](std::size_t k) { first[k] = positions(start[k]); });
  for (std::size_t k = 0; k < start.size(); ++k) frames[start[k]] = std::move(first[k]);
  std::vector<std::pair<double, double>> pending;
  for (auto it = frames.begin(); std::next(it) != frames.end(); ++it) pending.push_back({it->first, std::next(it)->first});
  double settled = 0.0;
  // An interval's verdict: its error (at 1/4, 1/2, 3/4, then, when within the
  // tolerance there, at the other k/16) and the positions at its middle.
  struct Verdict {
    double error = 0.0, where = 0.0;
    Points middle;
  };
  while (!pending.empty()) {
    std::vector<Verdict> verdicts(pending.size());
    for_each_index(pending.size(), large, [&](std::size_t i) {
      const auto [a, b] = pending[i];
      const Points& pa = frames.at(a);
      const Points& pb = frames.at(b);
      Verdict& v = verdicts[i];
      v.where = a;
      v.error = chord_error(positions, a, pa, b, pb, {0.25, 0.5, 0.75}, v.where, &v.middle);
      if (v.error <= tolerance) {
        v.error = std::max(v.error, chord_error(positions, a, pa, b, pb,
                                                {1 / 16., 2 / 16., 3 / 16., 5 / 16., 6 / 16., 7 / 16., 9 / 16.,
                                                 10 / 16., 11 / 16., 13 / 16., 14 / 16., 15 / 16.},
                                                v.where));
      }
    });
    std::vector<std::pair<double, double>> next;
    for (std::size_t i = 0; i < pending.size(); ++i) {
      const auto [a, b] = pending[i];
      Verdict& v = verdicts[i];
      const double mid = 0.5 * (a + b);
      const bool wide = b - a >= 2.0 * minimum_spacing * (hi - lo);
      if (v.error > tolerance && wide && mid > a && mid < b && frames.size() < maximum) {
        frames[mid] = std::move(v.middle);
        next.push_back({a, mid});
        next.push_back({mid, b});
      } else {
        settled += b - a;
        if (!wide && v.error > tolerance) {
          errors.narrow = std::max(errors.narrow, v.error);
          errors.narrow_width += b - a;
        } else if (v.error > errors.worst) {
          errors.worst = v.error;
          errors.worst_t = v.where;
        }
      }
      if (progress) progress(settled / (hi - lo), frames.size());
    }
    pending = std::move(next);
  }
  return frames;
}

std::vector<std::size_t> play_sequence(std::size_t keyframes, bool ping_pong) {
  std::vector<std::size_t> sequence;
  for (std::size_t k = 0; k < keyframes; ++k) sequence.push_back(k);
  if (ping_pong) {
    for (std::size_t k = keyframes - 1; k-- > 0;) sequence.push_back(k);
  }
  return sequence;
}

std::vector<float> sequence_times(const std::vector<double>& forward_seconds, const std::vector<std::size_t>& sequence) {
  const double total = forward_seconds.back();
  std::vector<float> times;
  for (std::size_t s = 0; s < sequence.size(); ++s) {
    const double forward = forward_seconds[sequence[s]];
    times.push_back(checked(s < forward_seconds.size() ? forward : 2.0 * total - forward));
  }
  return times;
}

void append_triangles(const Quad& q, std::vector<std::uint32_t>& out) {
  const std::vector<std::size_t> corners = distinct_corners(q);
  for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
    for (std::size_t c : {corners[0], corners[k], corners[k + 1]}) out.push_back(static_cast<std::uint32_t>(c));
  }
}

void build_morph(tinygltf::Model& model, BufferBuilder& buffer, const Design& design, const AssemblyMesh& mesh,
                 const MotionPath& path, const GltfOptions& options, GltfReport& report,
                 tinygltf::Value::Array& keyframe_t) {
  const Assembly& assembly = design.assembly;
  std::map<double, Points> frames;
  if (!options.static_t) {
    MorphErrors errors;
    const bool large = mesh.vertices.size() >= 2000;
    if (large) assembly.shared_vertices();  // evaluate() is thread-safe once they are known
    frames = morph_keyframes(path.positions, path.lo, path.hi, options.keyframes.relative_tolerance * assembly.model_size(),
                             std::max(options.keyframes.initial, path.minimum_keyframes),
                             std::min(options.max_morph_targets, options.keyframes.maximum),
                             options.keyframes.minimum_spacing, large, errors,
                             options.progress);
    report.max_vertex_error = errors.worst;
    report.vertex_error_t = errors.worst_t;
    report.narrow_vertex_error = errors.narrow;
    report.narrow_seconds = errors.narrow_width / (path.hi - path.lo) * path.seconds_of(path.hi);
  }
  const Points base = options.static_t ? path.positions_at_t(*options.static_t) : path.positions(path.rest);
  auto add_positions = [&](const std::vector<float>& data, bool with_bounds) {
    std::vector<double> lo3(3, INFINITY), hi3(3, -INFINITY);
    for (std::size_t k = 0; k < data.size(); ++k) {
      lo3[k % 3] = std::min(lo3[k % 3], static_cast<double>(data[k]));
      hi3[k % 3] = std::max(hi3[k % 3], static_cast<double>(data[k]));
    }
    const int view = buffer.add_view(data, TINYGLTF_TARGET_ARRAY_BUFFER);
    return buffer.add_accessor(view, 0, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, data.size() / 3,
                               with_bounds ? lo3 : std::vector<double>{}, with_bounds ? hi3 : std::vector<double>{});
  };
  std::vector<float> base_data;
  for (const Vec3& p : base) {
    for (int c = 0; c < 3; ++c) base_data.push_back(checked(p[c]));
  }
  const int base_accessor = add_positions(base_data, true);
  std::vector<int> targets;
  std::vector<double> target_t;
  for (const auto& [u, p] : frames) {
    std::vector<float> delta;
    for (std::size_t v = 0; v < p.size(); ++v) {
      for (int c = 0; c < 3; ++c) delta.push_back(checked(p[v][c] - static_cast<double>(base_data[v * 3 + c])));
    }
    targets.push_back(add_positions(delta, true));
    target_t.push_back(path.t_of(u));
  }
  tinygltf::Mesh m;
  m.name = assembly.name();
  for (std::size_t member = 0; member < assembly.member_count(); ++member) {
    std::vector<std::uint32_t> indices;
    // Which panels the primitive holds (a member's panels are consecutive) and
    // which of them are one triangle, for viewers that outline panels.
    std::size_t first = mesh.faces.size(), count = 0;
    tinygltf::Value::Array triangles;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      if (mesh.face_member[f] != member) continue;
      first = std::min(first, f);
      const std::size_t before = indices.size();
      append_triangles(mesh.faces[f], indices);
      if (indices.size() - before == 3) triangles.push_back(tinygltf::Value(static_cast<int>(count)));
      ++count;
    }
    if (indices.empty()) continue;
    const int view = buffer.add_view(indices, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    tinygltf::Primitive primitive;
    primitive.attributes["POSITION"] = base_accessor;
    primitive.indices = buffer.add_accessor(view, 0, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR,
                                            indices.size());
    primitive.material = static_cast<int>(member);
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    for (int target : targets) primitive.targets.push_back({{"POSITION", target}});
    tinygltf::Value::Object extras;
    extras["phedra_panels"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(static_cast<int>(first)),
                                                                     tinygltf::Value(static_cast<int>(count))});
    extras["phedra_triangles"] = tinygltf::Value(triangles);
    primitive.extras = tinygltf::Value(extras);
    m.primitives.push_back(primitive);
  }
  if (!targets.empty()) {
    m.weights.assign(targets.size(), 0.0);
    tinygltf::Value::Object extras;
    extras["targetNames"] = target_names(target_t);
    m.extras = tinygltf::Value(extras);
  }
  model.meshes.push_back(m);
  tinygltf::Node node;
  node.name = assembly.name();
  node.mesh = 0;
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.name = assembly.name();
  scene.nodes.push_back(0);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  report.panels = mesh.faces.size();
  report.keyframes = targets.size();
  if (targets.empty()) return;

  const std::size_t count = targets.size();
  std::vector<double> forward_seconds;
  for (const auto& [u, p] : frames) forward_seconds.push_back(path.seconds_of(u));
  const std::vector<std::size_t> sequence = play_sequence(count, options.ping_pong);
  const std::vector<float> times = sequence_times(forward_seconds, sequence);
  for (std::size_t k : sequence) keyframe_t.push_back(tinygltf::Value(target_t[k]));
  const int time_view = buffer.add_view(times, 0);
  const int time_accessor = buffer.add_accessor(time_view, 0, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR,
                                                times.size(), {times.front()}, {times.back()});
  // Weights: one row of `count` values per animation keyframe, zero but for the
  // keyframe's own target (sparse).
  std::vector<std::uint32_t> sparse_indices;
  std::vector<float> ones(sequence.size(), 1.0f);
  for (std::size_t s = 0; s < sequence.size(); ++s) {
    sparse_indices.push_back(static_cast<std::uint32_t>(s * count + sequence[s]));
  }
  const int index_view = buffer.add_view(sparse_indices, 0);
  const int value_view = buffer.add_view(ones, 0);
  tinygltf::Accessor weights;
  weights.bufferView = -1;
  weights.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  weights.type = TINYGLTF_TYPE_SCALAR;
  weights.count = sequence.size() * count;
  weights.sparse.isSparse = true;
  weights.sparse.count = static_cast<int>(sequence.size());
  weights.sparse.indices.bufferView = index_view;
  weights.sparse.indices.byteOffset = 0;
  weights.sparse.indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  weights.sparse.values.bufferView = value_view;
  weights.sparse.values.byteOffset = 0;
  model.accessors.push_back(weights);
  add_weights_animation(model, "fold", time_accessor, static_cast<int>(model.accessors.size()) - 1);
}

}  // namespace phedra::gltf
