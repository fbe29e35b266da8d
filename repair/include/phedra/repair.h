#pragma once
// The nearest buildable design (issue 14): varies the chosen numbers of a preset
// (design_variables.h) as little as possible, relative to the model size, so
// that every panel is simple and the motion is free of collisions over the
// required part of the flexion interval (docs/design.md, Repair). NLopt's
// Subplex drives summed constraint violations to zero, then minimises the
// squared distance under an exact penalty:
//  - panel shapes (MATH.md section 9): first the positive net (every general
//    edge along its axial one, every axial face simple), then every panel's
//    shape margin at least `shape_target`; cheap, from the input and from
//    `restarts` perturbed starts (the simple designs need not be connected);
//  - the motion, for simple designs only (t* and `motion_samples` samples a
//    side of the required part): no penetration, no hinge past shut.
// Every candidate is verified by the buildability report itself (200 samples
// a side), never by the optimizer's own figures.

#include "phedra/buildability.h"
#include "phedra/design_variables.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace phedra {

struct RepairOptions {
  std::vector<VariableGroup> vary{VariableGroup::apex_heights, VariableGroup::directions};
  /// Fields that stay as they are (JSON pointers, "/trajectory/3"): a handle the user holds.
  std::vector<std::string> fixed;
  /// The part of the flexion interval around t* that must be buildable: from
  /// t* towards each limit, this fraction of the way (1: all of it).
  double required_fraction = 1.0;
  /// When the required part cannot be reached: the widest part found (tried at
  /// 3/4, 1/2, 1/4 and t* alone), reported as such.
  bool widest_fallback = true;
  double shape_target = 0.005;       ///< the shape margin every panel keeps (room to edit)
  double edge_target = 0.005;        ///< while searching: the shortest panel edge, over the model size
  std::size_t motion_samples = 24;   ///< samples a side of the optimizer's motion margins
  std::size_t restarts = 40;         ///< perturbed starts after the input (for the panel shapes)
  std::size_t shape_candidates = 3;  ///< designs with simple panels to try the motion from
  std::size_t max_evaluations = 3000;  ///< per local search of the panel shapes (cheap: no motion)
  std::size_t motion_evaluations = 300;  ///< per search with the motion (each design sweeps it)
  double max_seconds = 60.0;         ///< in all
  unsigned seed = 1;
};

/// One preset field the repair changed.
struct FieldChange {
  std::string field;
  nlohmann::json before, after;
  double change = 0.0;    ///< after - before (a length), or the turn in degrees for a direction
  double relative = 0.0;  ///< |change| over the model size (a direction: the turn in radians)
};

struct RepairResult {
  /// A design buildable over the required part (or, with the fallback, over a
  /// smaller part around t*: `fraction` says how much) was found.
  bool found = false;
  bool already_buildable = false;  ///< the input met the requirement: nothing changed
  double fraction = 0.0;           ///< the part of the interval the result is buildable over (as required_fraction)
  nlohmann::json preset;           ///< the repaired preset object (when found)
  BuildabilityReport before, after;
  std::vector<FieldChange> changes;
  double distance = 0.0;           ///< relative to the model size (design_variables.h)
  std::size_t evaluations = 0;     ///< designs built by the search
  std::size_t starts = 0;          ///< local searches run
  double seconds = 0.0;
  std::vector<std::string> notes;  ///< what could not be varied
  /// When not found: how close it came and which constraint stayed violated.
  std::string closest;
  /// When not found: the closest design (the fewest panels not simple, then the
  /// widest buildable part), for inspection.
  nlohmann::json closest_preset;
};

/// Repairs `preset` (a preset object). InvalidInputError for a preset that does
/// not build and for bad options.
RepairResult repair(const nlohmann::json& preset, const RepairOptions& options = {});

/// The keep-buildable drag of the designer: how much a step may search.
struct ProjectionOptions {
  std::vector<VariableGroup> vary{VariableGroup::apex_heights};
  std::vector<std::string> fixed;  ///< the held handle's field (JSON pointer)
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
};

struct Projection {
  nlohmann::json preset;   ///< the design to show
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
/// keep-buildable drag keeps at every step.
bool buildable_at_t_star(const Design& design);

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

 private:
  std::string held_;
  std::vector<double> displacement_;
  double change_ = 0.0;
  int window_ = 0;
  nlohmann::json origin_;  ///< the preset when the drag of held_ began
  double origin_size_ = 0.0;  ///< its model size
};

/// `result` (a repaired or closest preset) named after the input: "NAME-repaired"
/// (or "NAME-closest" when `found` is false) with a description saying what was
/// varied (`vary`, as given) and its buildability.
nlohmann::json named_result(const nlohmann::json& result, const std::string& input_name, const std::string& vary,
                            const RepairResult& r);

/// The buildable part of a report as a fraction of the way from t* to each
/// limit (the smaller side): 1 for the whole interval, 0 for t* alone or none.
double buildable_fraction(const BuildabilityReport& report);

}  // namespace phedra
