#pragma once
// Cut sheets (issue 17): the panels unfolded into connected pieces that a maker
// cuts out, folds along marked lines and glues along labelled seams, laid out
// in assembly order on printable pages.
//
// A piece is a set of panels joined by hinges, unfolded flat: each panel keeps
// its true shape, seen from its front (the side its normal points to, as in
// the exports), so mountain and valley are read on the printed side. By default
// each strip (the panels between two profiles of a member) is one piece;
// `columns` joins the panels along the trajectory instead, `cells` unfolds each
// member of an array on its own (walls two cells share appear in both cells:
// glue them face to face), `panels` gives every panel its own piece. A piece
// that would overlap itself, or outgrow the page, is split. Hinges between
// pieces are seams: labelled S<k> on every side, a glue tab on one side.
// Panels that cannot be cut as one plate (bow-ties, degenerate) are pieces of
// their own, filled red.

#include "phedra/design.h"
#include "phedra/panel_shape.h"
#include "phedra/sheet_page.h"
#include "phedra/thick_plates.h"

#include <optional>
#include <string>
#include <vector>

namespace phedra {

enum class PieceMode { strips, columns, cells, panels };
PieceMode piece_mode_from_string(const std::string& name);  ///< throws InvalidInputError("--pieces")
std::string to_string(PieceMode mode);

/// A panel of a piece: its outline in the piece (mm), its corners' mesh vertices.
struct PiecePanel {
  std::size_t panel = 0;                  ///< P<k>: the panel's number in the exports
  std::size_t member = 0, row = 0, column = 0;
  Polygon2 outline;                       ///< 3 or 4 corners, counter-clockwise on the sheet
  std::vector<std::size_t> vertices;      ///< mesh vertex of each corner
  PanelShape shape = PanelShape::convex;
};

/// A hinge inside a piece: a fold line between two of its panels.
struct PieceFold {
  std::size_t first = 0, second = 0;      ///< indices into Piece::panels
  Vec2 a, b;                              ///< the line on the sheet (mm)
  double angle_degrees = 0.0;             ///< fold angle at t* (> 0 valley, seen from the printed side)
  LineStyle style = LineStyle::valley;    ///< mountain, valley or flat
};

/// One side of a seam: panel `panel`'s edge from corner `edge` to the next.
struct SeamSide {
  std::size_t seam = 0;                   ///< S<k>, from 1
  std::size_t panel = 0;                  ///< index into Piece::panels
  std::size_t edge = 0;
  std::optional<Polygon2> tab;            ///< the glue tab on this side, if any
  bool on_fold = false;                   ///< a fold line of this piece that a third panel (a wall) is glued to
};

struct Piece {
  std::size_t number = 0;                 ///< its place in the assembly order, from 1
  /// Thick plates: the outline a laser (or saw) cuts: the plate's top face (the
  /// bevels' inset, so the straight-cut plate lies inside the bevelled one)
  /// grown by half the kerf. The panel's hinge edges are then hinge lines.
  std::optional<Polygon2> cut;
  std::vector<PiecePanel> panels;
  std::vector<PieceFold> folds;
  std::vector<SeamSide> seams;
  std::vector<SheetText> labels;          ///< P<k> inside each panel, S<k> along each seam side
  bool cuttable = true;                   ///< false: one panel that is not a simple polygon
  /// Everything drawn: cut lines around it, fold lines, tab folds; tab and red fills.
  std::vector<SheetLine> lines() const;
  std::vector<SheetFill> fills() const;
  std::vector<Vec2> points() const;       ///< every outline and tab corner
};

/// Thick plates cut from sheet material (issue 27, item 3): one piece a plate.
struct PlateCut {
  double thickness_mm = 3.0;              ///< the material's thickness
  double kerf_mm = 0.0;                   ///< the width the cutter burns away: cut paths run half of it outside
  PlateSide side = PlateSide::automatic;
};

struct CutSheetOptions {
  PieceMode mode = PieceMode::strips;
  bool tabs = true;
  double tab_depth = 0.12;                ///< relative to the seam's length (at most max_tab_mm)
  double max_tab_mm = 6.0;
  std::optional<double> scale;            ///< mm per model unit; unset: the model size (of the panels within the size bounds) becomes `model_mm`
  double model_mm = 200.0;
  Vec2 page = Vec2(210.0, 297.0);         ///< mm (A4 portrait)
  double margin = 10.0;                   ///< mm around the page's content
  double gap = 3.0;                       ///< mm between pieces
  /// Thick plates instead of card: pieces are plates (PieceMode::panels, no tabs).
  std::optional<PlateCut> plates;
};
/// "a4", "letter", "a3" or "WxH" in mm.
Vec2 page_size_from_string(const std::string& name);  ///< throws InvalidInputError("--page")

struct CutSheets {
  std::string name;
  PieceMode mode = PieceMode::strips;
  double scale = 10.0;                    ///< mm per model unit
  Vec2 page;                              ///< mm
  Box2 content;                           ///< where pieces go on the first page (below the key)
  Box2 later_content;                     ///< on the later pages (below a title and one line: taller)
  const Box2& content_of(std::size_t k) const { return k == 0 ? content : later_content; }
  std::vector<Piece> pieces;              ///< placed on their pages (page coordinates, mm, y up)
  std::vector<std::size_t> piece_page;    ///< the page of each piece
  std::vector<SheetPage> pages;
  std::size_t seams = 0, folds = 0, tabs = 0;
  std::size_t untabbed_seams = 0;         ///< seams with no room for a tab on any side
  double smallest_label = 0.0;            ///< mm (capital height)
  std::size_t called_out = 0;             ///< labels beside their piece with a leader (no 2 mm room inside)
  /// What the legend shows besides the lines every sheet has.
  bool any_uncuttable = false, any_flat = false, any_seam_on_fold = false;
  /// Panels left off the sheets: oversized and slivers (panel_size.h), by number.
  std::vector<std::size_t> left_out;
  /// Thick plates: the plates' report (thickness in model units), the kerf, and
  /// the material: the pieces' cut area and the pages they use (the assembly
  /// page, the last, holds no piece).
  std::optional<ThickReport> thick;
  /// When the plates move over less than a tenth of the flexion interval: the
  /// thickest that fold over half of it (none: not even the thinnest do).
  bool hardly_fold = false;
  std::optional<ThickFolding> folding;
  double kerf_mm = 0.0, thickness_mm = 0.0;
  double cut_area_mm2 = 0.0;
  std::size_t piece_pages = 0;
  /// The part of the pages' area (those with pieces) the pieces cover.
  double material_used() const { return piece_pages ? cut_area_mm2 / (static_cast<double>(piece_pages) * page.x() * page.y()) : 0.0; }
};

/// When plates hardly fold (CutSheets::hardly_fold): what the first page and the
/// command say, in two sentences ("these 3 mm plates cannot fold: they cannot move
/// from t*", "plates up to 0.812 mm thick on the back side fold over half of it");
/// empty otherwise.
std::vector<std::string> plates_fold_words(const CutSheets& sheets);
/// The same for plates `thickness` thick in a unit (" mm" with `scale` mm a model
/// unit and the option --thickness-mm, or "" with 1 and --thickness) whose report
/// is `report`, `folding` the thickest that fold (thickest_folding); empty when
/// they move over a tenth of the flexion interval or more.
std::vector<std::string> plates_fold_words(const ThickReport& report, double thickness, double scale, const std::string& unit,
                                           const std::optional<ThickFolding>& folding);

/// The smallest capital height (mm) printed (issue 27: no label below 2 mm): a
/// label with less room inside its panel is called out beside its piece.
constexpr double readable_label_mm = 2.0;

/// The pieces, unfolded and labelled, in piece coordinates (mm), then laid out on pages.
CutSheets cut_sheets(const Design& design, const CutSheetOptions& options = {});

/// Renderers: one SVG per page (mm), a DXF of every page side by side (layers CUT,
/// MOUNTAIN, VALLEY, FLAT, TAB_FOLD, FRAME, LABELS); PDF and PNG: sheet_page.h.
std::string sheet_page_svg(const CutSheets& sheets, std::size_t page);
std::string cut_sheets_dxf(const CutSheets& sheets);
std::string cut_sheets_pdf(const CutSheets& sheets);

}  // namespace phedra
