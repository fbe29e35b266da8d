#pragma once
// Animated glTF 2.0 of a design (docs/formats.md): one node per rigid panel,
// nested along a spanning tree of the hinges with each node's origin on its
// hinge; the motion over the whole flexion interval as node rotations (and
// translations of the tree roots), keyframed so that no other hinge opens by
// more than a tolerance between keyframes. Y-up: glTF (x, y, z) = preset (x, z, -y).

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
  /// Morph targets instead of nodes: one mesh, one target per keyframe, sparse
  /// one-hot weights; keyframes bound the chord error of the vertices (at most
  /// `max_morph_targets`); they start from `keyframes.initial` and never exceed
  /// `keyframes.maximum` either.
  bool morph = false;
  std::size_t max_morph_targets = 250;
  KeyframeOptions keyframes;
  KeyframeProgress progress;  ///< called while the keyframes are chosen (node representation)
  /// Stored as asset.extras.phedra.buildability when not null
  /// (BuildabilityReport::file_json()): what every export says about the design.
  nlohmann::json buildability;
};

struct GltfReport {
  std::size_t panels = 0;
  std::size_t keyframes = 0;
  double max_opening = 0.0;  ///< nodes: largest opening of a non-tree hinge between keyframes; morph: largest
                             ///< distance of an interpolated vertex from its place (absolute)
  double opening_t = 0.0;
  double tolerance = 0.0;    ///< absolute
  double model_size = 0.0;
  std::size_t bytes = 0;
};

/// The glTF (or GLB) bytes. Throws Error(internal) rather than store a non-finite number.
std::string gltf_bytes(const Design& design, const GltfOptions& options, GltfReport* report = nullptr);

/// The Y-up map applied to every position: (x, y, z) -> (x, z, -y).
inline Vec3 to_y_up(const Vec3& p) { return Vec3(p.x(), p.z(), -p.y()); }

}  // namespace phedra
