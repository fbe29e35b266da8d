#pragma once
// The glTF exporter's parts (internal to exporters/): the buffer it fills, the
// motion an animation follows (t over the interval, or the configuration
// cycle, through the time map), the keyframes of morph targets, and the two
// representations (morph targets, a node per panel) that gltf_bytes assembles.

#include "phedra/assembly_mesh.h"
#include "phedra/gltf_export.h"
#include "phedra/time_map.h"

#include <tiny_gltf.h>

#include <cmath>
#include <functional>
#include <map>
#include <vector>

namespace phedra::gltf {

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

/// JSON as a glTF extras value (numbers that are whole stay integers).
tinygltf::Value to_value(const nlohmann::json& j);

/// A LINEAR animation `name` of node 0's morph weights: `times`, `weights` accessors.
void add_weights_animation(tinygltf::Model& model, const std::string& name, int times, int weights);

/// x as float32; Error(internal) rather than write a non-finite number.
float checked(double x);

/// "MEMBER panel (row,column)" of mesh face f.
std::string face_name(const Assembly& a, const AssemblyMesh& mesh, std::size_t f);

/// The triangles of a panel as mesh indices: two for a quad, one for a panel
/// whose two corners are one welded vertex (no zero-length edge, no sliver).
void append_triangles(const Quad& q, std::vector<std::uint32_t>& out);

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

/// t over the flexion interval (or options.range): `seconds` from its start to
/// its end, eased at the ends that are flexion limits.
MotionPath interval_path(const Design& design, const AssemblyMesh& mesh, const GltfOptions& options);

/// The configuration curve (PHedron::configuration_cycle): pass k is segment k,
/// on its branch, lasting `seconds` times its share of the interval, eased at
/// the flexion limits where it turns.
MotionPath cycle_path(const Design& design, const AssemblyMesh& mesh, const GltfOptions& options);

/// Keyframes for morph targets: vertex positions interpolate linearly, so an
/// interval is split at its midpoint until the chord error at 1/4, 1/2, 3/4 and
/// then at k/16 (k = 1..15) is within tolerance (or `maximum` keyframes are reached).
struct MorphErrors {
  double worst = 0.0, worst_t = 0.0;  ///< over intervals wide enough to split
  double narrow = 0.0, narrow_width = 0.0;  ///< over intervals left above the tolerance at the minimum spacing
};

/// Keyframes [lo, hi] -> positions (see MorphErrors), on two threads when `large`.
std::map<double, Points> morph_keyframes(const std::function<Points(double)>& positions, double lo, double hi,
                                          double tolerance, std::size_t initial, std::size_t maximum,
                                          double minimum_spacing, bool large, MorphErrors& errors,
                                          const KeyframeProgress& progress);

/// Keyframe k's place in the animation: forward, then (ping-pong) back again.
std::vector<std::size_t> play_sequence(std::size_t keyframes, bool ping_pong);

/// Animation times of a play sequence: forward times, mirrored about the end when going back.
std::vector<float> sequence_times(const std::vector<double>& forward_seconds, const std::vector<std::size_t>& sequence);

/// The morph-target representation: one node, one mesh (a primitive per member),
/// one target per keyframe, weights animated one-hot (stored sparse). A static
/// export (options.static_t) is the mesh at that t with no targets.
void build_morph(tinygltf::Model& model, BufferBuilder& buffer, const Design& design, const AssemblyMesh& mesh,
                 const MotionPath& path, const GltfOptions& options, GltfReport& report,
                 tinygltf::Value::Array& keyframe_t);

/// The node representation: one node per panel on a hinge spanning tree.
void build_nodes(tinygltf::Model& model, BufferBuilder& buffer, const Design& design, const AssemblyMesh& mesh,
                 const MotionPath& path, const GltfOptions& options, GltfReport& report,
                 tinygltf::Value::Array& keyframe_t);

}  // namespace phedra::gltf
