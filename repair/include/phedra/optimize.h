#pragma once
// Inverse design (issue 26, item 1): the design nearest the input whose
// metamaterial figures (metamaterial_metrics.h, by the names of figure_names())
// meet targets, kept buildable (the notion of `phedra check`) unless asked not
// to. docs/design.md, Inverse design: the method, the variables, what binds.
//
// The search varies the chosen preset numbers (design_variables.h, ties kept)
// to minimise the summed squared target errors, each over its tolerance, plus
// an exact penalty on the repair's constraints (panel shapes and size bounds,
// no collision at t*) and a small pull towards the input; then every candidate
// that reaches the targets is verified by the metrics and the buildability
// report themselves (the whole interval swept), and when the motion collides
// the search goes on with the motion in its constraints.

#include "phedra/design_variables.h"
#include "phedra/homogenized_strain.h"
#include "phedra/panel_size.h"
#include "phedra/repair.h"

#include <nlohmann/json.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace phedra {

struct FigureTarget {
  enum class Kind { equal, at_least, at_most };
  std::string name;  ///< a figure_names() entry
  Kind kind = Kind::equal;
  double value = 0.0;
  /// "poisson.nu_12=-0.8", "flexion_width>=0.5": InvalidInputError("--target", ...)
  /// naming the known figures for an unknown name, and for a value that is not a number.
  static FigureTarget parse(const std::string& text);
  std::string to_string() const;
};

/// Points a design at t* should pass near (a "surface" file: {"points": [[x, y, z], ...]}).
struct FitTarget {
  std::vector<Vec3> points;
  double tolerance = 0.0;  ///< the RMS distance that counts as reached (model units)
  /// The turn of the points the search starts each fit from (set by optimize from the input).
  std::shared_ptr<Mat3> start;
  /// InvalidInputError("--fit", ...) naming the file and the bad entry.
  static std::vector<Vec3> read_points(const std::string& path);
  /// InvalidInputError(field, where + ...) unless there are 3 points or more, all
  /// finite, spanning a plane (not all on one point or one line: the rigid
  /// alignment of the fit would be undefined).
  static void check_points(const std::vector<Vec3>& points, const std::string& field, const std::string& where);
};

/// The best rigid motion of `points` onto a design's panels at t*: the RMS
/// distance then, and the turn of the points (about their centroid).
struct SurfaceFit {
  double rms = 0.0;
  Mat3 turn = Mat3::Identity();
};
SurfaceFit best_fit(const Design& design, const std::vector<Vec3>& points);

/// The RMS distance from `points` to the design's panels at t* after the best
/// rigid motion of the points (iterated closest points, from the points as
/// given and from 48 turns that put their normal (least spread) on the
/// design's, either way up, spun about it).
/// With `start`: one descent from that turn of the points, which it updates
/// (what a search does from one design to the next).
double fit_distance(const Design& design, const std::vector<Vec3>& points, Mat3* start = nullptr);

struct OptimizeOptions {
  std::vector<FigureTarget> targets;
  std::optional<FitTarget> fit;
  std::vector<VariableGroup> vary{VariableGroup::apex_heights, VariableGroup::directions};
  std::vector<std::string> fixed;  ///< JSON pointers held at their value
  bool keep_buildable = true;
  double relative_tolerance = 0.02;  ///< an equality target is met within max(this x |value|, absolute)
  double absolute_tolerance = 0.01;
  double max_seconds = 60.0;
  std::size_t samples = 101;  ///< the metrics' samples (deployment and volume ratios)
  MetricsAxes axes = MetricsAxes::structural;
  SizeBounds bounds;
  unsigned seed = 1;
  /// Designs to start from besides the input (an atlas's best rows, atlas_starts):
  /// {label, preset of the input's layout}; the search begins at the best of them.
  std::vector<std::pair<std::string, nlohmann::json>> starts;
};

/// One target's outcome, as the metrics code computes it on the result.
struct TargetOutcome {
  std::string target;              ///< as given ("poisson.nu_12=-0.8", "fit<=0.05")
  std::optional<double> before, after;  ///< none: undefined on that design
  bool met = false;
  double error = 0.0;              ///< distance from meeting it, over its tolerance (0 when met)
};

struct OptimizeResult {
  bool reached = false;
  nlohmann::json preset;  ///< the best design found (reached or the closest)
  std::vector<TargetOutcome> targets;
  bool buildable = false;  ///< of the result (whole interval swept)
  std::string buildability;  ///< its summary
  std::string binding;       ///< when not reached: the target furthest from its goal, and what stops it
  std::size_t evaluations = 0;
  double seconds = 0.0;
  double distance = 0.0;  ///< from the input, relative to the model size
  std::vector<FieldChange> changes;  ///< the fields that differ from the input
  std::vector<std::string> notes;
  std::string started_from;  ///< the start's label ("atlas row 17"), empty: the input
};

/// The rows of the atlas at `path` (docs/atlas.md) an optimization best starts
/// from: done and valid (and buildable, when keep_buildable and the atlas has
/// it), ranked by the targets' errors over their tolerances on the atlas's
/// figures (NaN: far), then by row; at most `count`, each {"atlas row K",
/// its preset}. InvalidInputError("--start") when the atlas has none of the
/// targets' figures or no such row.
std::vector<std::pair<std::string, nlohmann::json>> atlas_starts(const std::string& path, const OptimizeOptions& options,
                                                                 std::size_t count);

/// `result` named "NAME-optimized" (or "NAME-closest" when not reached) with a
/// description of the targets, what was varied and its buildability.
nlohmann::json named_optimized(const nlohmann::json& result, const std::string& input_name, const std::string& vary,
                               const OptimizeResult& r);

/// Optimizes `preset` (a preset object). InvalidInputError for a preset that
/// does not build, no targets, and bad options.
OptimizeResult optimize(const nlohmann::json& preset, const OptimizeOptions& options);

/// The outcomes of `targets` on `design` (the metrics recomputed): what the
/// command prints for the written file.
std::vector<TargetOutcome> evaluate_targets(const Design& design, const OptimizeOptions& options);

}  // namespace phedra
