#pragma once
// Keyframes for the node animation: the panels' local poses at chosen t, so
// that interpolating them (slerp of rotations, lerp of root translations) never
// puts a vertex further than a tolerance from its exact place at the same
// animation time (the parameter here is time-like: the glTF exporter passes the
// time map's segment parameter, time_map.h), nor opens a hinge outside the tree (or a vertex shared
// between members) by more. Intervals are split at their midpoint until both
// measured at 1/4, 1/2 and 3/4 of every interval are within the tolerance; then
// every interval is measured again at 15 points (k/16) and split where needed.

#include "phedra/panel_tree.h"

#include <functional>
#include <vector>

namespace phedra {

struct KeyframeOptions {
  /// Largest accepted opening, relative to the model size.
  double relative_tolerance = 1e-3;
  /// Keyframes to start with, evenly spread over the interval (>= 2).
  std::size_t initial = 9;
  /// Never more than this many (the opening reported says what was reached).
  std::size_t maximum = 4000;
  /// No two keyframes closer than this fraction of [lo, hi] (0.8 ms of a 4 s
  /// animation, 0.02 frame at 24 fps: Blender merges keyframes closer than 0.01
  /// frame, and float32 times cannot tell them apart). With time linear in t
  /// next to a flexion limit (--ease 0) the motion moves as the square root of
  /// the distance to the limit, so the interval touching it may stay above the
  /// tolerance: reported apart.
  double minimum_spacing = 2e-4;
};

struct Keyframes {
  std::vector<double> t;
  std::vector<std::vector<RigidPose>> local;  ///< per keyframe, per panel
  double max_opening = 0.0;                   ///< largest opening found between keyframes (absolute)
  double opening_t = 0.0;                     ///< where
  double max_vertex_error = 0.0;              ///< largest distance of a vertex from its exact place (absolute)
  double vertex_error_t = 0.0;                ///< where
  /// The larger of vertex error and opening inside intervals left above the
  /// tolerance because they are already as short as `minimum_spacing` allows
  /// (next to a flexion limit), and their total width; the figures above leave them out.
  double narrow_vertex_error = 0.0;
  double narrow_width = 0.0;
  double tolerance = 0.0;                     ///< absolute
};

/// Progress: the fraction of [lo, hi] whose keyframes are final, and the keyframe count.
using KeyframeProgress = std::function<void(double, std::size_t)>;

/// `positions(t)` gives the mesh's vertex positions at t; `groups` are sets of
/// (panel, corner) that must coincide (every mesh vertex's copies, and vertices
/// shared between members).
Keyframes choose_keyframes(const PanelTree& tree, const std::function<Points(double)>& positions, double lo,
                           double hi, const std::vector<std::vector<std::pair<std::size_t, int>>>& groups,
                           double model_size, const KeyframeOptions& options, const KeyframeProgress& progress = {});

/// Local poses interpolated between two keyframes (fraction s in [0, 1]).
std::vector<RigidPose> interpolate_poses(const std::vector<RigidPose>& a, const std::vector<RigidPose>& b, double s);

}  // namespace phedra
