#pragma once
// A printed page as drawing primitives (lines, fills, labels in boxes), in mm
// with y up, and its renderers: SVG (one page), PDF (several, cairo) and PNG.
// Cut sheets and crease patterns are drawn with them; legends and scale bars
// are built the same way on both.

#include "phedra/sheet_geometry.h"

#include <optional>
#include <string>
#include <vector>

namespace phedra {

enum class LineStyle { cut, mountain, valley, flat, tab_fold, frame, axis, hinge, leader };
/// Fills. The view_* styles are faces of a small 3D view (the assembly pages):
/// filled and outlined, drawn in order (far to near), so nearer faces hide
/// farther ones: pieces already joined, the ones this step adds, the rest.
enum class FillStyle { tab, not_cuttable, swatch_tab, swatch_not_cuttable, marker, view_joined, view_added, view_later };
enum class TextRole { panel, seam, title, legend, note, warning };  ///< warning: bold, dark red (what stops a build)

struct SheetLine {
  Vec2 a, b;
  LineStyle style = LineStyle::cut;
  /// A line of the key (the legend's samples, the scale bar): drawn in its
  /// style, never cut (the DXF's KEY layer, the SVG's key group).
  bool key = false;
};
struct SheetFill {
  Polygon2 outline;
  FillStyle style = FillStyle::tab;
  std::optional<std::size_t> panel;  ///< not_cuttable: the panel (P<k>)
};
/// A label: its text fills `box` (capital height = box.height, advance = box.width), reading along box.axis.
struct SheetText {
  std::string text;
  Box2 box;
  TextRole role = TextRole::panel;
  /// A label called out beside its piece (no room inside for 2 mm): the point
  /// inside its panel (or on its seam) that a leader line joins it to.
  std::optional<Vec2> leader = std::nullopt;
};

struct SheetPage {
  std::vector<SheetLine> lines;
  std::vector<SheetFill> fills;
  std::vector<SheetText> texts;
  std::vector<std::size_t> pieces;        ///< cut sheets: indices into CutSheets::pieces on this page
};

/// Font size giving capital height h (DejaVu Sans and Helvetica: capitals 0.72 em).
double font_size_for_capitals(double h);

/// The advance of `text` at capital height `height` in DejaVu Sans (bold: its
/// bold face), from the font's widths (the renderers stretch it to exactly
/// this: with the font, not at all); a character beyond ASCII as wide as a digit.
double text_width(const std::string& text, double height, bool bold = false);

/// A left-aligned text of capital height h with its baseline at `at`.
void add_text(SheetPage& page, const std::string& text, Vec2 at, double h, TextRole role = TextRole::legend);

/// Legend items flowing along rows from (left, top) to `right`, a new row when one is full.
class Legend {
 public:
  Legend(SheetPage& page, double left, double right, double top, double height = 2.2)
      : page_(page), left_(left), right_(right), x_(left), row_(top), h_(height) {}
  void line(LineStyle style, const std::string& what);
  void fill(FillStyle style, const std::string& what);
  /// A label as it appears on the sheet, then what it means.
  void sample(const std::string& label, TextRole role, const std::string& what);
  /// A remark in the flow of the items.
  void note(const std::string& what);
  /// A remark that stops a build (plates that cannot fold): bold, dark red.
  void warning(const std::string& what);
  double bottom() const { return row_; }

 private:
  void room(double width);
  SheetPage& page_;
  double left_, right_, x_, row_, h_;
};

/// A scale bar at `at` (its left end), of a round length in mm (1-2-5 steps, at
/// most `longest`), labelled with what it is in model units.
void add_scale_bar(SheetPage& page, Vec2 at, double scale, double longest);

/// Renderers. `title` goes to the SVG's <title> and the PDF's metadata.
/// A number of a page (a length in mm, an angle in degrees) as text, to four decimals.
std::string sheet_number(double x);

/// The layer a line is on, in the DXF and as the SVG's groups: CUT, HINGE,
/// MOUNTAIN, VALLEY, FLAT, TAB_FOLD, AXIS, FRAME, LABELS (leaders), KEY (the key's lines).
const char* layer_name(const SheetLine& line);

/// The page as SVG (mm): its lines in one group a layer (Inkscape layers,
/// named as layer_name), the cut outlines closed polygons in pure red
/// (#ff0000, 0.25 mm: the colour laser software maps to a vector cut), nothing
/// else in that colour; the fills and labels as printed.
std::string page_svg(const SheetPage& page, Vec2 size, const std::string& title);
std::string pages_pdf(const std::vector<SheetPage>& pages, Vec2 size, const std::string& title);
std::string page_png(const SheetPage& page, Vec2 size, double dpi = 150.0);

}  // namespace phedra
