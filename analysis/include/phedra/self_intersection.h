#pragma once
// Self-intersection of a design over its flexion interval (issue 7, item 3).
// Panels are the distinct panels of panel_mesh(design), numbered as in every
// exported file: coupled members welded, a wall two cells share tested once
// (interior walls included). Two kinds of collision:
//  - panels that cut into each other (non-adjacent panels, and panels that meet
//    at a corner), triangle by triangle (triangle_overlap.h) with a uniform grid
//    as broad phase;
//  - a hinge folding through: the two panels on an edge close onto each other
//    (dihedral opening 0 or 360 degrees), tracked continuously from t*.
// Touching is not intersecting: contact without penetration is allowed, so a
// hinge that folds flat onto itself ends the free interval exactly there, unless
// that happens at the flexion limit itself (a tube that folds flat at the end of
// its motion): `lower_contact` / `upper_contact` say so.
// The sweep walks from t* to each flexion limit over samples that crowd towards
// the limit (the motion is fastest there), and bisects the first collision to
// 1e-12 of the interval's width. A collision that starts and ends between two
// samples can be missed: more samples, finer resolution.

#include "phedra/assembly_mesh.h"
#include "phedra/design.h"
#include "phedra/panel_id.h"
#include "phedra/panel_shape.h"

#include <nlohmann/json.hpp>

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace phedra {

struct SelfIntersectionOptions {
  /// Samples from t* to each limit (limits included); they crowd quadratically towards the limit.
  std::size_t samples_per_side = 200;
  /// Penetration (and hinge closing angle) that counts, relative to the model size.
  double relative_tolerance = 1e-9;
  /// The free interval also ends where the bounding-box diagonal passes this many
  /// times the one at t* (SizeBounds::max_growth; 0: no bound).
  double max_growth = 10.0;
};

/// What ends an intersection-free stretch.
struct Collision {
  /// growth: not a collision but the size bound (a = b = a panel of the vertex
  /// furthest out): the design grows past max_growth times its size at t*.
  enum class Kind { panels, hinge, growth };
  Kind kind = Kind::panels;
  PanelId a, b;
  double t = 0.0;  ///< where it starts (the end of the free interval)
  double growth = 0.0;  ///< growth: the bound it passes (max_growth)
};

struct InvalidPanel {
  PanelId panel;
  PanelShape shape = PanelShape::degenerate;
};

struct SelfIntersectionReport {
  std::string name;
  double t_star = 0.0;
  double t_lambda = 0.0, t_mu = 0.0;   ///< the flexion interval
  double free_lower = 0.0, free_upper = 0.0;  ///< the intersection-free sub-interval around t*
  std::optional<Collision> at_t_star;  ///< the input configuration itself intersects
  double depth_at_t_star = 0.0;        ///< then: how deeply its panels cut into each other (a length)
  std::optional<Collision> lower, upper;  ///< what ends the free interval (empty: the flexion limit)
  std::optional<Collision> lower_contact, upper_contact;  ///< panels that touch at the flexion limit, no earlier
  std::vector<InvalidPanel> invalid_panels;  ///< bow-tie and degenerate panels (left out of the test)
  std::size_t members = 1, panels = 0, hinges = 0, samples = 0;
  double model_size = 0.0;

  /// No collision anywhere in the flexion interval (invalid panels aside).
  bool intersection_free() const { return !at_t_star && !lower && !upper; }
  nlohmann::json to_json() const;
};

std::ostream& operator<<(std::ostream& out, const SelfIntersectionReport& report);

/// The shape of every panel at t* (the motion keeps it): the invalid ones.
std::vector<InvalidPanel> invalid_panels(const Design& design);

SelfIntersectionReport find_self_intersections(const Design& design, const SelfIntersectionOptions& options = {});

/// The configuration at t* alone (one snapshot, no sweep): its first collision.
std::optional<Collision> self_intersection_at_t_star(const Design& design, const SelfIntersectionOptions& options = {});

/// How far the configuration at t* is from a collision there (`c`, as
/// self_intersection_at_t_star found it), as a number a change of the design
/// drives up: for a hinge, its opening from shut (radians, min(angle, 2 pi -
/// angle)); for panels, minus the sum of every penetration at t* over the model
/// size (0: none). NaN when the design has no such hinge or panels.
double collision_margin_at_t_star(const Design& design, const Collision& c);

/// "panel 3 (strip 0, column 3) and panel 9 (strip 1, column 2) penetrate", naming
/// members when there are several; `contact`: a touch at a flexion limit ("touch (no more)").
std::string describe(const Collision& collision, bool several_members, bool contact = false);

/// How badly a motion collides, as numbers a search can drive to zero.
struct MotionMargins {
  double depth = 0.0;   ///< the deepest penetration of two simple panels at any sample (> 0: they cut; a length)
  /// The penetrations of every penetrating pair added up, at the sample where
  /// that sum is largest: a search sees each pair it separates, not only the deepest.
  double depth_sum = 0.0;
  double folded = 0.0;  ///< the furthest any hinge went past shut (radians; > 0 folded through, <= 0 fine)
  double growth = 1.0;  ///< the largest bounding-box diagonal at a sample over the one at t*
  double t_depth = 0.0, t_folded = 0.0;  ///< where
};

/// The motion over [from, to] (a part of the flexion interval containing t*):
/// t* and `samples_per_side` samples towards each end, crowding towards it; an
/// end that is a flexion limit is left out (contact is allowed there).
MotionMargins motion_margins(const Design& design, double from, double to, std::size_t samples_per_side,
                             const SelfIntersectionOptions& options = {});

/// Every panel that penetrates another at t, or whose hinge has folded through
/// on the way from t* to t (tracked over `steps` samples), sorted, each once.
/// Contact (panels touching, a hinge folded flat) is not a collision.
std::vector<std::size_t> colliding_panels(const Design& design, double t, std::size_t steps = 64,
                                          const SelfIntersectionOptions& options = {});

/// The intersection-free sub-interval, or InvalidInputError("--no-self-intersection")
/// when the configuration at t* itself intersects.
std::pair<double, double> intersection_free_interval(const SelfIntersectionReport& report);

}  // namespace phedra
