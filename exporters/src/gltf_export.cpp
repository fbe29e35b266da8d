#include "phedra/gltf_export.h"

#include "phedra/assembly_check.h"
#include "phedra/assembly_mesh.h"
#include "phedra/errors.h"
#include "phedra/panel_tree.h"
#include "phedra/time_map.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <sstream>
#ifndef __EMSCRIPTEN__
#include <thread>
#endif

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

/// Keyframes for morph targets: vertex positions interpolate linearly, so an
/// interval is split at its midpoint until the chord error at 1/4, 1/2, 3/4 and
/// then at k/16 (k = 1..15) is within tolerance (or `maximum` keyframes are reached).
struct MorphErrors {
  double worst = 0.0, worst_t = 0.0;  ///< over intervals wide enough to split
  double narrow = 0.0, narrow_width = 0.0;  ///< over intervals left above the tolerance at the minimum spacing
};

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

/// The triangles of a panel as mesh indices: two for a quad, one for a panel
/// whose two corners are one welded vertex (no zero-length edge, no sliver).
void append_triangles(const Quad& q, std::vector<std::uint32_t>& out) {
  const std::vector<std::size_t> corners = distinct_corners(q);
  for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
    for (std::size_t c : {corners[0], corners[k], corners[k + 1]}) out.push_back(static_cast<std::uint32_t>(c));
  }
}

/// What an animation follows: a parameter u over [lo, hi], segment k of the
/// time map (time_map.h) for u in [k, k + 1] with u - k the fraction of its time,
/// the Y-up mesh positions there, the t it stands for and its animation time.
struct MotionPath {
  double lo = 0.0, hi = 1.0;
  double rest = 0.0;                ///< u of the configuration at t* (the rest pose)
  std::size_t minimum_keyframes = 2;  ///< evenly spread start keyframes needed (segment boundaries)
  TimeMap time;
  std::function<Points(double)> positions;
  std::function<Points(double)> positions_at_t;  ///< on the input branch (static exports)
  std::function<double(double)> t_of;
  std::function<double(double)> seconds_of;
};

Points y_up(Points p) {
  for (Vec3& x : p) x = to_y_up(x);
  return p;
}

/// A path over the segments of `time`, segment k on the branch `flipped[k]` (empty: the input branch).
MotionPath segment_path(const Assembly& a, const AssemblyMesh& mesh, TimeMap time,
                        std::vector<std::vector<bool>> flipped) {
  auto map = std::make_shared<const TimeMap>(std::move(time));
  auto branches = std::make_shared<const std::vector<std::vector<bool>>>(std::move(flipped));
  MotionPath path;
  path.time = *map;
  path.lo = 0.0;
  path.hi = static_cast<double>(map->segments.size());
  path.minimum_keyframes = 2 * map->segments.size() + 1;
  auto segment = [map](double u) {
    return std::min(static_cast<std::size_t>(std::max(u, 0.0)), map->segments.size() - 1);
  };
  path.seconds_of = [map, segment](double u) {
    const TimeSegment& s = map->segments[segment(u)];
    const double phi = std::clamp(u - static_cast<double>(segment(u)), 0.0, 1.0);
    return s.start + phi * (s.end - s.start);
  };
  path.t_of = [map, segment, seconds = path.seconds_of](double u) { return map->segments[segment(u)].t_at(seconds(u)); };
  path.positions = [&a, &mesh, branches, segment, t_of = path.t_of](double u) {
    AssemblyConfiguration c;
    const std::vector<bool>& branch = (*branches)[segment(u)];
    if (branch.empty()) {
      a.evaluate(t_of(u), c);
    } else {
      a.evaluate(t_of(u), branch, c);
    }
    return y_up(mesh.positions(c));
  };
  path.positions_at_t = [&a, &mesh](double t) { return y_up(mesh.positions(a.evaluate(t))); };
  return path;
}

/// Whether t is a flexion limit of the design (within rounding of the interval's width).
bool at_flexion_limit(const Assembly& a, double t) {
  const FlexionInterval& f = a.flexion_interval();
  const double slack = 1e-12 * std::max(1.0, std::abs(f.upper.t - f.lower.t));
  return std::abs(t - f.lower.t) <= slack || std::abs(t - f.upper.t) <= slack;
}

/// t over the flexion interval (or options.range): `seconds` from its start to
/// its end, eased at the ends that are flexion limits.
MotionPath interval_path(const Design& design, const AssemblyMesh& mesh, const GltfOptions& options) {
  const Assembly& a = design.assembly;
  const double lo = options.range ? options.range->first : a.flexion_interval().lower.t;
  const double hi = options.range ? options.range->second : a.flexion_interval().upper.t;
  TimeSegment s;
  s.start = 0.0;
  s.end = options.seconds;
  s.t0 = lo;
  s.t1 = hi;
  const double ease = options.ease * options.seconds;
  s.ease0 = ease_at_end(at_flexion_limit(a, lo), ease, options.seconds);
  s.ease1 = ease_at_end(at_flexion_limit(a, hi), ease, options.seconds);
  TimeMap time;
  time.segments = {s};
  time.ping_pong = options.ping_pong;
  MotionPath path = segment_path(a, mesh, time, {std::vector<bool>{}});
  path.minimum_keyframes = 2;
  path.rest = hi > lo ? std::clamp(s.seconds_at(a.t_star()) / options.seconds, 0.0, 1.0) : 0.0;
  return path;
}

/// The configuration curve (PHedron::configuration_cycle): pass k is segment k,
/// on its branch, lasting `seconds` times its share of the interval, eased at
/// the flexion limits where it turns.
MotionPath cycle_path(const Design& design, const AssemblyMesh& mesh, const GltfOptions& options) {
  const Assembly& a = design.assembly;
  if (options.static_t) throw InvalidInputError("--cycle", "a static export (--at) has no cycle");
  if (options.range) {
    throw InvalidInputError("--cycle", "the configuration curve runs through the flexion limits; it cannot be "
                                       "restricted to a sub-interval (--no-self-intersection)");
  }
  const std::vector<PHedron::Pass>& passes = a.base().configuration_cycle().passes;
  const double width = a.flexion_interval().width();
  TimeMap time;
  time.ping_pong = options.ping_pong;
  std::vector<std::vector<bool>> flipped;
  double start = 0.0;
  for (const PHedron::Pass& p : passes) {
    TimeSegment s;
    s.start = start;
    s.end = start + std::abs(p.to - p.from) / width * options.seconds;
    s.t0 = p.from;
    s.t1 = p.to;
    const double ease = options.ease * options.seconds;
    s.ease0 = ease_at_end(at_flexion_limit(a, p.from), ease, s.end - s.start);
    s.ease1 = ease_at_end(at_flexion_limit(a, p.to), ease, s.end - s.start);
    time.segments.push_back(s);
    flipped.push_back(p.flipped);
    start = s.end;
  }
  MotionPath path = segment_path(a, mesh, time, flipped);
  path.rest = 0.0;
  return path;
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

/// Keyframe k's place in the animation: forward, then (ping-pong) back again.
std::vector<std::size_t> play_sequence(std::size_t keyframes, bool ping_pong) {
  std::vector<std::size_t> sequence;
  for (std::size_t k = 0; k < keyframes; ++k) sequence.push_back(k);
  if (ping_pong) {
    for (std::size_t k = keyframes - 1; k-- > 0;) sequence.push_back(k);
  }
  return sequence;
}

/// Animation times of a play sequence: forward times, mirrored about the end when going back.
std::vector<float> sequence_times(const std::vector<double>& forward_seconds, const std::vector<std::size_t>& sequence) {
  const double total = forward_seconds.back();
  std::vector<float> times;
  for (std::size_t s = 0; s < sequence.size(); ++s) {
    const double forward = forward_seconds[sequence[s]];
    times.push_back(checked(s < forward_seconds.size() ? forward : 2.0 * total - forward));
  }
  return times;
}

/// The morph-target representation: one node, one mesh (a primitive per member),
/// one target per keyframe, weights animated one-hot (stored sparse). A static
/// export (options.static_t) is the mesh at that t with no targets.
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
  tinygltf::Animation animation;
  animation.name = "fold";
  tinygltf::AnimationSampler sampler;
  sampler.input = time_accessor;
  sampler.output = static_cast<int>(model.accessors.size()) - 1;
  sampler.interpolation = "LINEAR";
  animation.samplers.push_back(sampler);
  tinygltf::AnimationChannel channel;
  channel.sampler = 0;
  channel.target_node = 0;
  channel.target_path = "weights";
  animation.channels.push_back(channel);
  model.animations.push_back(animation);
}

/// JSON as a glTF extras value (numbers that are whole stay integers).
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

/// extras.phedra.time_map: how time maps to t (time_map.h, docs/formats.md).
tinygltf::Value time_map_value(const TimeMap& time, double ease_seconds) {
  auto pair = [](double a, double b) { return tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(a), tinygltf::Value(b)}); };
  tinygltf::Value::Array segments;
  for (const TimeSegment& s : time.segments) {
    tinygltf::Value::Object o;
    o["seconds"] = pair(s.start, s.end);
    o["t"] = pair(s.t0, s.t1);
    o["ease_seconds"] = pair(s.ease0, s.ease1);
    segments.push_back(tinygltf::Value(o));
  }
  tinygltf::Value::Object out;
  out["ease_seconds"] = tinygltf::Value(ease_seconds);
  out["segments"] = tinygltf::Value(segments);
  out["ping_pong"] = tinygltf::Value(time.ping_pong);
  return tinygltf::Value(out);
}

/// The node representation: one node per panel on a hinge spanning tree.
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

}  // namespace

std::string gltf_bytes(const Design& design, const GltfOptions& options, GltfReport* report) {
  const Assembly& assembly = design.assembly;
  AssemblyMesh mesh = panel_mesh(design);
  mesh.faces = welded_faces(mesh, coincident_vertices(mesh, assembly));
  const MotionPath path = options.cycle ? cycle_path(design, mesh, options) : interval_path(design, mesh, options);
  const double size = assembly.model_size();
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

  GltfReport figures;
  figures.tolerance = options.keyframes.relative_tolerance * size;
  figures.model_size = size;
  tinygltf::Value::Array keyframe_t;
  if (options.morph) {
    build_morph(model, buffer, design, mesh, path, options, figures, keyframe_t);
  } else {
    build_nodes(model, buffer, design, mesh, path, options, figures, keyframe_t);
  }

  if (!options.static_t) figures.vertex_error_t = path.t_of(figures.vertex_error_t);
  tinygltf::Value::Object phedra;
  phedra["name"] = tinygltf::Value(assembly.name());
  phedra["kind"] = tinygltf::Value(design.kind);
  phedra["t_lambda"] = tinygltf::Value(assembly.flexion_interval().lower.t);
  phedra["t_mu"] = tinygltf::Value(assembly.flexion_interval().upper.t);
  if (options.range && !options.static_t) {
    phedra["animated_interval"] =
        tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(options.range->first), tinygltf::Value(options.range->second)});
  }
  phedra["t_star"] = tinygltf::Value(assembly.t_star());
  phedra["model_size"] = tinygltf::Value(size);
  phedra["up"] = tinygltf::Value(std::string("glTF (x, y, z) = preset (x, z, -y)"));
  if (options.static_t) {
    phedra["t"] = tinygltf::Value(*options.static_t);
  } else {
    phedra["seconds"] = tinygltf::Value(options.seconds);
    if (options.cycle) {
      tinygltf::Value::Array passes;
      for (const PHedron::Pass& pass : assembly.base().configuration_cycle().passes) {
        tinygltf::Value::Object p;
        p["from"] = tinygltf::Value(pass.from);
        p["to"] = tinygltf::Value(pass.to);
        p["switched_strip"] = tinygltf::Value(static_cast<int>(pass.switched));
        passes.push_back(tinygltf::Value(p));
      }
      phedra["cycle"] = tinygltf::Value(passes);
    }
    phedra["ping_pong"] = tinygltf::Value(options.ping_pong);
    phedra["keyframe_t"] = tinygltf::Value(keyframe_t);
    phedra["time_map"] = time_map_value(path.time, options.ease * options.seconds);
    // Measured at 15 points of every keyframe interval (absolute, model units).
    phedra["max_vertex_error"] = tinygltf::Value(figures.max_vertex_error);
    phedra["max_vertex_error_t"] = tinygltf::Value(figures.vertex_error_t);
    phedra["vertex_tolerance"] = tinygltf::Value(figures.tolerance);
    // Next to a flexion limit: keyframe intervals at the minimum spacing still above the tolerance.
    phedra["limit_vertex_error"] = tinygltf::Value(figures.narrow_vertex_error);
    phedra["limit_seconds"] = tinygltf::Value(figures.narrow_seconds);
    phedra["minimum_keyframe_spacing_seconds"] =
        tinygltf::Value(options.keyframes.minimum_spacing * path.seconds_of(path.hi));
    if (!options.morph) {
      phedra["max_hinge_opening"] = tinygltf::Value(figures.max_opening);
      phedra["hinge_tolerance"] = tinygltf::Value(figures.tolerance);
    }
  }
  phedra["representation"] = tinygltf::Value(std::string(options.morph ? "morph targets" : "nodes"));
  phedra["panels"] = tinygltf::Value(static_cast<int>(figures.panels));
  if (!options.morph) phedra["tree_depth"] = tinygltf::Value(static_cast<int>(figures.tree_depth));
  // The check figures over the interval, relative to the model size, for viewers.
  const AssemblyCheckReport check = check_assembly(assembly, {});
  tinygltf::Value::Object check_figures;
  check_figures["passed"] = tinygltf::Value(check.passed());
  check_figures["planarity"] = tinygltf::Value(check.planarity.value / size);
  check_figures["isometry"] = tinygltf::Value(check.isometry.value / size);
  check_figures["closure"] = tinygltf::Value(check.closure.value / size);
  check_figures["shared_vertices"] = tinygltf::Value(check.shared.value / size);
  check_figures["samples"] = tinygltf::Value(static_cast<int>(check.samples));
  phedra["check"] = tinygltf::Value(check_figures);
  if (!options.buildability.is_null()) phedra["buildability"] = to_value(options.buildability);
  if (!options.preset_text.empty()) phedra["preset"] = tinygltf::Value(options.preset_text);
  tinygltf::Value::Object extras;
  extras["phedra"] = tinygltf::Value(phedra);
  // Where clients read it: three.js keeps asset.extras in parser.json; Blender's
  // importer drops it but keeps scenes[0].extras as the scene's custom properties.
  model.asset.extras = tinygltf::Value(extras);
  model.scenes[0].extras = tinygltf::Value(extras);

  tinygltf::TinyGLTF writer;
  std::ostringstream out;
  if (!writer.WriteGltfSceneToStream(&model, out, !options.binary, options.binary)) {
    throw Error(ExitCode::internal, "glTF serialisation failed");
  }
  std::string bytes = out.str();
  if (report) {
    *report = figures;
    report->bytes = bytes.size();
  }
  return bytes;
}

}  // namespace phedra
