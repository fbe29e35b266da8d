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

/// What "nearest" means (--objective).
enum class RepairObjective {
  distance,  ///< the smallest distance (design_variables.h): small changes, spread over many fields
  fields,    ///< the fewest fields changed (then the smallest distance among those tried)
};

struct RepairOptions {
  std::vector<VariableGroup> vary{VariableGroup::apex_heights, VariableGroup::directions};
  /// Fields that stay as they are (JSON pointers, "/trajectory/3"): a handle the user holds.
  std::vector<std::string> fixed;
  /// The part of the flexion interval around t* that must be buildable: from
  /// t* towards each limit, this fraction of the way (1: all of it).
  double required_fraction = 1.0;
  /// When the required part cannot be reached: search the widest part that can
  /// (tried at 3/4, 1/2, 1/4 and t* alone) for the closest design. Never a
  /// result: `found` means the required part is reached.
  bool search_widest = true;
  double shape_target = 0.005;       ///< the shape margin every panel keeps (room to edit)
  /// t* stays at least this part of the flexion interval away from each limit
  /// (or half the input's own distance, when smaller): at a limit two profile
  /// planes coincide, the positions are ill-conditioned and a side is empty.
  double t_star_margin = 0.01;
  double edge_target = 0.005;        ///< while searching: the shortest panel edge, over the model size
  std::size_t motion_samples = 24;   ///< samples a side of the optimizer's motion margins
  std::size_t restarts = 40;         ///< perturbed starts after the input (for the panel shapes)
  std::size_t shape_candidates = 3;  ///< designs with simple panels to try the motion from
  std::size_t max_evaluations = 3000;  ///< per local search of the panel shapes (cheap: no motion)
  std::size_t motion_evaluations = 300;  ///< per search with the motion (each design sweeps it)
  /// Scattered designs tried when the local searches from the input find no design
  /// with simple panels and t* free of collisions (repair_search.h, scatter_search).
  std::size_t scatter_samples = 4000;
  double max_seconds = 60.0;         ///< in all
  /// When no design is found varying `vary` and the trajectory is not among
  /// them: search again with the trajectory varied too (60 % of the time for the
  /// first search then), and say so (RepairResult::escalated, a note).
  bool escalate = true;
  /// When nothing is found and time is left: this many more searches from other
  /// random starts (seed + 1, seed + 2, ...), each with the time left.
  unsigned retries = 2;
  /// fields: after the nearest design, the same requirement met varying only the
  /// largest 1, 2, 4, ... of its changes (a search each, all other fields held),
  /// the first that succeeds kept; up to max_seconds more.
  RepairObjective objective = RepairObjective::distance;
  /// What counts as buildable by size (--max-growth): the repaired design keeps within them.
  SizeBounds bounds;
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
  /// A design buildable over the required part was found (a smaller part is
  /// never a result: it is the closest design, `closest_fraction` says how much).
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
  std::vector<std::string> notes;  ///< what could not be varied, and the escalation
  std::vector<VariableGroup> varied;  ///< what the result varied (options.vary, or more after an escalation)
  bool escalated = false;             ///< the trajectory was added to what varies (RepairOptions::escalate)
  /// The fields the nearest design (RepairObjective::distance) changed; with
  /// RepairObjective::fields the result changes `changes.size()` <= this many.
  std::size_t nearest_changes = 0;
  /// When not found: how close it came and which constraint stayed violated.
  std::string closest;
  /// When not found: the closest design (the fewest panels not simple, then the
  /// widest buildable part), for inspection.
  nlohmann::json closest_preset;
  /// When not found: the part of the interval the closest design is buildable
  /// over (as required_fraction; 0 when not even at t*).
  double closest_fraction = 0.0;
};

/// Repairs `preset` (a preset object). InvalidInputError for a preset that does
/// not build and for bad options.
RepairResult repair(const nlohmann::json& preset, const RepairOptions& options = {});

/// `result` (a repaired or closest preset) named after the input: "NAME-repaired"
/// (or "NAME-closest" when `found` is false) with a description saying what was
/// varied (`vary`, as given) and its buildability.
nlohmann::json named_result(const nlohmann::json& result, const std::string& input_name, const std::string& vary,
                            const RepairResult& r);

/// Every number that differs between two presets, as fields (directions as turns), lengths relative to `size`.
std::vector<FieldChange> changes_between(const nlohmann::json& before, const nlohmann::json& after, double size,
                                         const nlohmann::json::json_pointer& at = nlohmann::json::json_pointer());

/// The buildable part of a report as a fraction of the way from t* to each
/// limit (the smaller side): 1 for the whole interval, 0 for t* alone or none.
double buildable_fraction(const BuildabilityReport& report);

}  // namespace phedra
