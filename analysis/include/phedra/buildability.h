#pragma once
// Whether a design can be built, over which part of its motion, and why not:
// the one notion every command, export and the designer report (MATH.md
// section 9). A design is buildable over [a, b] when every panel is simple
// (convex, or non-convex with one reflex corner; the triangles of boundary
// columns are fine) within the size bounds (no panel oversized or a sliver,
// panel_size.h) and, for every t in [a, b], no two panels penetrate, no hinge
// folds through (contact at a flexion limit is allowed) and the design stays
// within max_growth times its size at t*. Panels are the
// distinct panels of panel_mesh(design), numbered as in every exported file; a
// wall two cells share is one panel of both.

#include "phedra/design.h"
#include "phedra/panel_diagnosis.h"
#include "phedra/panel_size.h"
#include "phedra/self_intersection.h"

#include <nlohmann/json.hpp>

#include <iosfwd>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace phedra {

/// The samples a side for a sweep that should cost about what 2000 panels at 200
/// samples cost: 200 up to 2000 panels, fewer above (at least 24).
std::size_t sweep_samples_for(std::size_t panels);

struct BuildabilityOptions {
  /// samples_per_side 0: sweep_samples_for(the design's panel count).
  SelfIntersectionOptions sweep;
  DiagnosisOptions diagnosis;
  /// The size bounds (panel_size.h): they override diagnosis.size and sweep.max_growth.
  SizeBounds bounds;
  /// Sweep the motion for collisions (false: panel shapes and t* alone).
  bool sweep_motion = true;
};

struct BuildabilityReport {
  std::string name, kind;
  std::size_t panels = 0;        ///< distinct panels
  std::size_t shared_walls = 0;  ///< of them, walls two cells share
  std::size_t members = 1;
  double t_star = 0.0, t_lambda = 0.0, t_mu = 0.0;
  /// Panels that are not simple, with their causes (panel order).
  std::vector<PanelDiagnosis> invalid;
  /// The smallest shape_margin of any panel (negative: a panel is crossed).
  double shape_margin = 0.0;
  /// Collisions of the simple panels over the flexion interval (or at t* alone
  /// without the sweep: then free_lower = free_upper = t*).
  SelfIntersectionReport motion;
  bool swept = true;
  /// Members whose kind crosses itself at every t (anti-parallelogram tubes:
  /// their L_0 is a crossed four-bar, MATH.md section 6): not a mistake in the numbers.
  std::vector<std::size_t> self_crossing_members;
  /// When the configuration at t* collides (and hints were asked for, with the
  /// preset): the fields that open the hinge or separate the panels (field_hints.h).
  std::vector<FieldHint> collision_hints;

  std::size_t count(PanelShape shape) const;
  bool panels_simple() const { return invalid.empty(); }
  /// The buildable part of the flexion interval around t*; empty when a panel is
  /// not simple or the configuration at t* collides.
  std::optional<std::pair<double, double>> interval() const;
  /// Buildable over [a, b] (within the flexion interval).
  bool buildable_over(double a, double b) const;
  /// Buildable over the whole flexion interval.
  bool buildable() const { return buildable_over(t_lambda, t_mu); }
  /// One line: "buildable over the whole flexion interval [a, b]", or what is wrong.
  std::string summary() const;
  /// The panel list of the invalid ones: "44, 66, 70 (and 7 more)".
  std::string invalid_list(std::size_t shown = 8) const;
  nlohmann::json to_json() const;
  /// What exported files store: buildable, the summary, the counts, the numbers
  /// of the invalid panels (and their shapes), the buildable interval.
  nlohmann::json file_json() const;
};

/// Text report: the summary, every invalid panel with its cause and the fields
/// to change (the first `detail` panels), and what ends the buildable interval.
std::ostream& operator<<(std::ostream& out, const BuildabilityReport& report);

/// `preset` (the preset object the design was built from) enables field hints.
BuildabilityReport assess_buildability(const Design& design, const nlohmann::json* preset = nullptr,
                                       const BuildabilityOptions& options = {});

}  // namespace phedra
