#pragma once
// Why a panel cannot be cut as one plate, in terms of the input (MATH.md
// section 9). Every edge of the general net G is a constant signed multiple
// (its scale) of the same edge of the axial net A, so a corner of G turns like
// the corner of A times the signs of the two edge scales meeting there. A panel
// of G is therefore crossed (a bow-tie) for exactly one of these causes:
//  - its axial face is crossed, and the scales keep it so;
//  - its axial face is simple, but one edge scale has the other sign than the
//    other three: two profile edges (or two transversal edges) of the panel point
//    opposite ways relative to A (one shrank through zero between them);
//  - a boundary-column face: the transversal edge scale q lies in (0, 1), so the
//    boundary edge (q - 1 times the same axial edge) runs the same way as it.
// docs/design.md derives the rule and the causes.

#include "phedra/design.h"
#include "phedra/panel_nets.h"
#include "phedra/panel_size.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace phedra {

enum class PanelCause {
  none,                    ///< the panel is simple
  axial_face_crossed,      ///< the axial face is crossed and the edge scales keep it so
  edge_reversed,           ///< one edge scale has the other sign than the panel's other three
  boundary_segment_short,  ///< boundary column: transversal scale q in (0, 1)
  degenerate,              ///< no area: its corners are collinear (or the axial face is degenerate)
  oversized,               ///< simple, but its longest edge beyond SizeBounds::max_edge_ratio of the median panel's
  sliver,                  ///< simple, but its area below SizeBounds::min_aspect of its longest edge squared
};

std::string to_string(PanelCause cause);

/// Section 9 applied to one panel.
struct ShapeRule {
  PanelShape axial = PanelShape::convex;      ///< the axial face (a boundary face's triangle counts as convex)
  PanelShape predicted = PanelShape::convex;  ///< G's shape from A's corner turns and the scale signs
  std::array<double, 4> scales{1.0, 1.0, 1.0, 1.0};  ///< signed scale of edge k (corner k to k + 1); boundary: of the transversal edge(s)
  PanelCause cause = PanelCause::none;
  int odd_edge = -1;  ///< edge_reversed: the edge whose scale sign differs from the other three
};

ShapeRule apply_shape_rule(const PanelNets& nets);

/// How far a panel is from the crossed shapes, dimensionless: positive for a
/// simple panel, negative for a crossed one, about the sine of the corner angle
/// (or the relative edge scale) that would have to pass through zero. The
/// triangles of strip 0's boundary columns are 1. For searches and repairs.
double shape_margin(const PanelNets& nets);

/// A preset field to change to make a panel simple, and which way.
struct FieldHint {
  std::string field;    ///< as errors name fields: "apex_heights[3]", "trajectory[5][2]", "grid.u_heights[1]"
  double value = 0.0;   ///< its value now
  /// First-order change that brings one corner turn of the panel to zero (the
  /// edge of the crossed region); its sign is the direction. Go somewhat past it.
  double change = 0.0;
};

struct PanelDiagnosis {
  std::size_t panel = 0;  ///< its number: the face index in panel_mesh (the exported mesh)
  std::size_t member = 0, strip = 0, column = 0;  ///< where it is in its member's grid
  std::optional<MemberFace> shared_with;          ///< a wall two cells share: the other cell's face
  PanelShape shape = PanelShape::degenerate;      ///< what it is (geometry at t*)
  ShapeRule rule;
  std::string why;                ///< the cause in terms of the input
  std::vector<FieldHint> hints;   ///< best first; empty when no field was tried or none helps
};

struct DiagnosisOptions {
  /// Compute field hints (two constructions of the design per candidate field).
  bool hints = true;
  /// Panels that get hints (the first ones); the others get a cause only.
  std::size_t max_hinted_panels = 24;
  /// Panels beyond these bounds are oversized or slivers (max_growth is the sweep's).
  SizeBounds size;
};

/// Every panel of `mesh` (panel_mesh(design)) that is not simple, with its
/// cause. `preset` (the preset object the design was built from) enables the
/// field hints; without it they are left empty.
std::vector<PanelDiagnosis> diagnose_panels(const Design& design, const AssemblyMesh& mesh,
                                            const nlohmann::json* preset = nullptr, const DiagnosisOptions& options = {});

/// "increase apex_heights[3] (now 1) by more than about 0.41"
std::string describe(const FieldHint& hint);

/// A number for people: 4 significant digits.
std::string format_short(double value);

}  // namespace phedra
