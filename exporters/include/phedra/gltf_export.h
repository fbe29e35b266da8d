#pragma once
// Animated glTF 2.0 of a design (docs/formats.md), in one of two representations:
// - morph targets (the default): one mesh of the distinct panels, one morph
//   target per keyframe, one-hot weights; what scales (10^4 panels open in
//   Blender in seconds, one draw call per member in three.js);
// - nodes: one rigid node per panel, nested along a spanning tree of the hinges
//   rooted in the middle of the design, each node's origin on its hinge; the
//   motion as node rotations (and translations of the tree roots); panels stay
//   exactly rigid between keyframes (small models).
// Keyframes are chosen so that, between two of them, every vertex stays within
// a tolerance of the exact configuration at the same time (t from time by the
// time map stored in the file, time_map.h: linear but at the flexion limits), and
// (nodes) no hinge outside the tree opens by more. Y-up: glTF (x, y, z) = preset (x, z, -y).

#include "phedra/design.h"
#include "phedra/keyframes.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

namespace phedra {

struct GltfOptions {
  bool binary = true;                 ///< .glb (true) or .gltf with an embedded buffer
  double seconds = 4.0;               ///< duration of t_lambda -> t_mu
  bool ping_pong = false;             ///< play t_lambda -> t_mu -> t_lambda
  /// Fraction of `seconds` eased at each end that is a flexion limit (time_map.h):
  /// there t's distance from the limit grows as the square of time, so that the
  /// motion, which moves as the square root of that distance, keeps a bounded
  /// speed. 0: time linear in t throughout (then the keyframe intervals touching
  /// a limit can stay above the tolerance: reported as narrow_vertex_error).
  double ease = 1.0 / 16.0;
  /// Animate the whole configuration curve through the flexion limits
  /// (PHedron::configuration_cycle: t* -> t_mu -> ... -> t*, strips switching
  /// branch at the limits; an array's members follow its base). Each pass takes
  /// `seconds` times its share of the interval.
  bool cycle = false;
  std::optional<double> static_t;     ///< a static export at this t (no animation)
  /// Animate [range.first, range.second] (a sub-interval of the flexion interval,
  /// e.g. the intersection-free one) instead of the whole interval; `seconds`
  /// is then its duration. Not with `cycle`.
  std::optional<std::pair<double, double>> range;
  /// Morph targets (true, the default) or a node per panel (false). Morph: one
  /// mesh, one target per keyframe, sparse one-hot weights, at most
  /// `max_morph_targets` targets (and never more than `keyframes.maximum`).
  bool morph = true;
  std::size_t max_morph_targets = 250;
  KeyframeOptions keyframes;
  KeyframeProgress progress;  ///< called while the keyframes are chosen
  /// Stored as extras.phedra.buildability when not null
  /// (BuildabilityReport::file_json()): what every export says about the design.
  nlohmann::json buildability;
  /// Stored as extras.phedra.preset when not empty: the preset the file was
  /// generated from, as JSON text (a string: every client keeps strings), so
  /// that viewers can export it and its FOLD, and open it in the designer.
  std::string preset_text;
};

struct GltfReport {
  std::size_t panels = 0;
  std::size_t keyframes = 0;
  /// Largest distance, between keyframes, of a vertex as the file interpolates
  /// it from its exact place at the same t (absolute; measured at 15 points of
  /// every keyframe interval), and the t where.
  double max_vertex_error = 0.0;
  double vertex_error_t = 0.0;
  /// Keyframe intervals already as short as KeyframeOptions::minimum_spacing
  /// allows (next to a flexion limit, where the motion moves as the square root
  /// of the distance to it) are not split further: their largest vertex error
  /// (absolute) and their total animation time, apart from max_vertex_error.
  double narrow_vertex_error = 0.0;
  double narrow_seconds = 0.0;
  /// Nodes: largest opening of a hinge outside the tree between keyframes (absolute; 0 for morph targets).
  double max_opening = 0.0;
  double tolerance = 0.0;    ///< absolute
  double model_size = 0.0;
  std::size_t tree_depth = 0;  ///< nodes: levels of the hinge tree
  std::size_t bytes = 0;
};

/// The glTF (or GLB) bytes. Throws Error(internal) rather than store a non-finite number.
std::string gltf_bytes(const Design& design, const GltfOptions& options, GltfReport* report = nullptr);

/// The Y-up map applied to every position: (x, y, z) -> (x, z, -y).
inline Vec3 to_y_up(const Vec3& p) { return Vec3(p.x(), p.z(), -p.y()); }

}  // namespace phedra
