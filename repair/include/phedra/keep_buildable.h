#pragma once
// The designer's keep-buildable drag (issue 14): each step of a drag keeps every
// panel simple and the configuration at t* free of collisions, moving other
// fields than the held one along cheap lines first, then with repair's shape
// search (docs/design.md, "Keep buildable").

#include "phedra/design.h"
#include "phedra/design_variables.h"
#include "phedra/t_star_collisions.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace phedra {

/// The keep-buildable drag of the designer: how much a step may search.
struct ProjectionOptions {
  std::vector<VariableGroup> vary{VariableGroup::apex_heights};
  /// The held handle's field first (JSON pointer), then any others that stay
  /// (e.g. the field that defines t*).
  std::vector<std::string> fixed;
  std::size_t max_evaluations = 200;
  double max_seconds = 0.012;      ///< within a 60 Hz frame with the redraw
  /// A drag continues: how the previous step moved the varied fields
  /// (Projection::displacement, scaled to this step), tried first.
  std::vector<double> continue_along;
  /// How far the held field moved in this step when it is one number (an apex
  /// height; 0: unknown): its neighbours moving along with it are tried next.
  double held_change = 0.0;
  /// The preset when the drag began: for a held trajectory point, the points
  /// next to it following its move since then are tried (a soft selection over
  /// windows of 1, 2, 4, ... 32 points a side, a tent falloff), from
  /// `first_window` (an index into those: the one the drag's last step used).
  nlohmann::json drag_origin;
  int first_window = 0;
  /// The model size of drag_origin (0: unknown). A projected design may not be
  /// larger than 1.25 times the larger of it and that of drag_origin with the
  /// held field moved (without a drag origin: 1.5 times the input's): a
  /// trajectory edge turned nearly into its profile plane sends the axial net
  /// far out while every panel stays simple.
  double origin_size = 0.0;
  /// The collision check at t*, kept between the steps of a drag (KeepBuildableDrag's:
  /// only what moved is tested again); null: each check from scratch.
  TStarCollisions* collisions = nullptr;
};

struct Projection {
  nlohmann::json preset;   ///< the design to show
  std::optional<Design> design;  ///< it, built (the caller need not build it again)
  bool moved = false;      ///< other fields than the held one changed
  std::size_t evaluations = 0;
  /// How the varied fields moved (DesignVariables order, the held one 0): for
  /// the next step's continue_along.
  std::vector<double> displacement;
  /// How it was found: "already", "continued", "neighbours", "trajectory", "search".
  std::string how;
  int window = -1;  ///< "trajectory": the index of the window of points that followed
};

/// Every panel simple and the configuration at t* free of collisions: what a
/// keep-buildable drag keeps at every step (`collisions`: the check at t* to use).
bool buildable_at_t_star(const Design& design, TStarCollisions* collisions = nullptr);

/// One step of a keep-buildable drag: `preset` itself when every panel is simple
/// and t* is free of collisions, else the nearest such design changing only
/// `vary` but not the held fields, found within the budget (the motion over
/// the interval is checked when the hand stops); nullopt when none was found.
/// Cheap first (a drag's steps are small and alike): along the previous step's
/// displacement, then with the held height's neighbours moving along (one
/// side, the other, both, two a side), or a held trajectory point's neighbours
/// following its move since the drag began (drag_origin; they are not among
/// the varied fields, the line moves them nonetheless: a dense trajectory has
/// no other way out of a reversed segment); on the first such line that reaches a
/// buildable design, the nearest point of it (bisection, 1/4 of the line).
/// Then, with time left, the optimizer as repair's shape stage.
/// InvalidInputError when `preset` does not build.
std::optional<Projection> project_buildable(const nlohmann::json& preset, const ProjectionOptions& options = {});

/// The steps of one keep-buildable drag: each is project_buildable of the
/// preset with the held field moved, continuing along the last projected
/// step's displacement (scaled by how far the held number moved now against
/// then). A step that needed no projection, or found none, ends the continuation.
class KeepBuildableDrag {
 public:
  /// `preset` has the held field (JSON pointer `held`) at its new value; it was
  /// `previous` (a number or a point) before this step. As project_buildable.
  std::optional<Projection> step(const nlohmann::json& preset, const std::string& held, const nlohmann::json& previous,
                                 ProjectionOptions options = {});

  /// buildable_at_t_star with this drag's collision check (the designer's stop at the wall).
  bool buildable(const Design& design) { return buildable_at_t_star(design, &collisions_); }

 private:
  std::string held_;
  std::vector<double> displacement_;
  double change_ = 0.0;
  int window_ = 0;
  nlohmann::json origin_;  ///< the preset when the drag of held_ began
  double origin_size_ = 0.0;  ///< its model size
  TStarCollisions collisions_;  ///< kept from step to step (and from drag to drag)
};

}  // namespace phedra
