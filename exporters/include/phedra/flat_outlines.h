#pragma once
// Fabrication: the flat outline of every panel (issue 7, item 6), laid out on
// one sheet, labelled with its panel id and the id of the hinge on each edge,
// with optional glue tabs, as SVG or DXF. Panels are those of the exported mesh
// (an assembly's merged mesh when it is merged, else its members side by side);
// they are rigid, so their outlines are the same at every t.
//
// Hinge k joins the panels that share an edge of the mesh; cut every outline,
// then join the edges that carry the same hinge label. With tabs, each hinge
// gets one tab, on the panel with the lower id: glue it under the other panel.

#include "phedra/design.h"
#include "phedra/panel_shape.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace phedra {

struct OutlineOptions {
  bool tabs = false;         ///< a glue tab on one side of every hinge
  double tab_depth = 0.12;   ///< tab depth, relative to the hinge's length (tapered 45 degrees)
  double spacing = 0.02;     ///< gap between panels on the sheet, relative to the model size
  double scale = 10.0;       ///< sheet units (mm in the SVG) per model unit
};

struct FlatPanel {
  std::size_t face = 0, member = 0, row = 0, column = 0;
  std::array<Vec2, 4> corners;                     ///< placed on the sheet (mesh corner order)
  std::array<std::optional<std::size_t>, 4> hinge;  ///< edge k (corner k to k + 1): its hinge id, if any
  std::array<bool, 4> tab{};                       ///< edge k carries the hinge's tab
  PanelShape shape = PanelShape::convex;           ///< a bow-tie or degenerate one is flagged on the sheet
  bool cuttable() const { return is_valid_panel(shape); }
};

struct OutlineSheet {
  std::string name;
  std::vector<FlatPanel> panels;
  std::size_t hinges = 0;
  double width = 0.0, height = 0.0;
  double tab_depth = 0.12;
  double label_size = 0.0;  ///< text height

  /// The tab polygon of panel p's edge k (4 points, outside the panel).
  std::array<Vec2, 4> tab_polygon(const FlatPanel& p, int k) const;
};

OutlineSheet flat_outlines(const Design& design, const OutlineOptions& options = {});

std::string outlines_svg(const OutlineSheet& sheet);
/// AutoCAD R12 ASCII DXF: layers CUT (outlines and tabs), FOLD (edges under tabs), LABELS (text).
std::string outlines_dxf(const OutlineSheet& sheet);

}  // namespace phedra
