#pragma once
// Which preset field moves a panel towards a simple shape, and which way: the
// derivative of the panel's corner turns (general net, t*) with respect to each
// numeric field of the preset, by central differences of the whole
// construction. The change that brings a corner turn to zero, to first order,
// is the hint; the smallest one relative to the field's scale comes first.

#include "phedra/assembly_mesh.h"
#include "phedra/design.h"
#include "phedra/panel_diagnosis.h"
#include "phedra/self_intersection.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace phedra {

/// A numeric field of a preset a user may change to reshape panels.
struct DesignField {
  enum class Group { heights, trajectory, directions };
  std::string name;                  ///< "apex_heights[3]", "trajectory[5][2]", "couplings[1].free_height"
  nlohmann::json::json_pointer pointer;
  Group group = Group::heights;
  std::optional<std::size_t> row;    ///< the trajectory point or direction it belongs to
  double scale = 1.0;                ///< the length its changes are measured against
};

/// The length fields of a preset: apex heights of every kind (core, tube, grid,
/// row, couplings), trajectory coordinates (polyline points, spline control
/// points, helix centre, radius and rise) and direction coordinates.
std::vector<DesignField> design_fields(const nlohmann::json& preset, double model_size);

/// What a hint aims at for one face.
struct HintGoal {
  enum class Kind {
    turns,   ///< a corner turn through zero (a crossed panel becomes simple)
    edge,    ///< edge `edge` (corner edge to edge + 1) down to `value` long (an oversized panel)
    aspect,  ///< area over longest edge squared up to `value` (a sliver)
  };
  Kind kind = Kind::turns;
  int edge = 0;
  double value = 0.0;
};

/// Hints for each of `faces` (member faces of `design`, built from `preset`):
/// up to two, from different field groups, best first. Trajectory and direction
/// fields are tried only within one row of a face's strip. `goals` (one per
/// face; missing ones: turns) says what each face's hint aims at.
std::vector<std::vector<FieldHint>> field_hints(const nlohmann::json& preset, const Design& design,
                                                const std::vector<MemberFace>& faces,
                                                const std::vector<HintGoal>& goals = {});

/// The opening a hint for a hinge shut at t* aims at (10 degrees).
constexpr double collision_hint_opening = 0.17453292519943295;

/// Hints for a collision at t* (`collision`, as self_intersection_at_t_star
/// finds it on `design`, built from `preset`): the fields whose first-order
/// change opens a shut hinge to collision_hint_opening, or separates
/// penetrating panels (collision_margin_at_t_star up to 0); each field's change
/// tried both ways (the margin has a kink where the collision starts). Up to
/// two, from different field groups, smallest change relative to its scale first.
std::vector<FieldHint> collision_hints(const nlohmann::json& preset, const Design& design, const Collision& collision);

}  // namespace phedra
