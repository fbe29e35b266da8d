#pragma once
// The stages of cut_sheets (cut_sheets.h): unfolding pieces, placing their
// labels, laying them out on pages.

#include "phedra/cut_sheets.h"

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace phedra::sheets {

/// Pieces in piece coordinates (mm): unfolded, folds and seams found, tabs chosen.
/// `fit`: the largest box (mm) a piece may grow to (either way round), tabs aside.
/// Oversized panels and slivers (panel_size.h) are left off: their numbers go to
/// `left_out`, and their edges carry no seam label.
std::vector<Piece> unfold_pieces(const Design& design, const CutSheetOptions& options, double scale, Vec2 fit,
                                 std::size_t& seams, std::vector<std::size_t>& left_out);

/// Fills piece.labels: S<k> along every seam side, then P<k> inside every panel.
void place_labels(Piece& piece);

/// Single-panel pieces (PieceMode::panels, no tabs) turned into plates: the cut
/// outline (the plate's top face at `scale` mm a model unit, grown by half of
/// `kerf_mm`), labels inside it (the piece's number and panel, the seams along
/// the hinge edges). Pieces whose panel has no plate stay as they are.
void cut_plates(std::vector<Piece>& pieces, const ThickPlates& plates, double scale, double kerf_mm);

/// A page listing the assembly: every piece, the earlier pieces it is hinged
/// (plates) or glued (card) to and along which seams, how the hinges go on or
/// the pieces fold and glue.
std::vector<SheetPage> assembly_pages(const CutSheets& sheets);

/// Pages of small 3D views of the assembly as it grows (issue 27: "a small 3D
/// view of each step"): up to 12 views a page, each after a group of pieces,
/// the plates already joined grey, the ones the group adds orange, the rest
/// white, at t* from one fixed oblique direction (faces drawn far to near).
/// `mesh` and `x`: the panels and their positions at t*.
std::vector<SheetPage> assembly_views(const CutSheets& sheets, const AssemblyMesh& mesh, const Points& x);

/// The largest label box (capital height at most max_height) inside `outline`,
/// along edge `edge` (from corner edge to the next; reading upright either
/// way) or, without edge, centred on the panel; clear of `avoid`. Nothing if
/// not even a tenth of a millimetre fits.
std::optional<Box2> fit_label(const Polygon2& outline, std::optional<std::size_t> edge, const std::string& text,
                              double max_height, const std::vector<Box2>& avoid);

/// The same rectangle, read the other way when its text would be upside down (y up).
Box2 upright(const Box2& box);

/// A label with no room inside: an empty box at `anchor` (a point inside its
/// panel: panel_anchor, seam_anchor) for call_out_small_labels.
Box2 no_room(const Vec2& anchor);
Vec2 panel_anchor(const Polygon2& region);
Vec2 seam_anchor(const Polygon2& outline, std::size_t edge);
/// How many of the labels are at least readable_label_mm high.
std::size_t readable_inside(const std::vector<SheetText>& labels);

/// Every label of the piece lower than readable_label_mm (2 mm) called out:
/// readable_label_mm high beside the piece, clear of its panels, tabs and other
/// labels, nearest to the point it names (its box's centre, or an empty box's
/// origin), which its `leader` keeps.
void call_out_small_labels(Piece& piece);

/// Cells of a page's content area (or of a piece) that are taken: the grid the
/// pieces are nested on (sheet_nesting.cpp). Cell (x, y) is [x, x + 1) x [y, y + 1)
/// cells from the grid's origin, y up.
class CellMask {
 public:
  CellMask(int width, int height);
  /// The cells within `reach` (mm) of the shapes (mm, in [0, size]), cells of
  /// `cell` mm, with `pad` cells of room on every side (shape coordinate 0 is
  /// cell pad).
  static CellMask of_shapes(const std::vector<Polygon2>& shapes, const Vec2& size, double cell, double reach, int pad);
  int width() const { return width_; }
  int height() const { return height_; }
  bool get(int x, int y) const;
  void set(int x, int y);
  /// Whether `other`, its cell (0, 0) on this one's (dx, dy), meets a taken cell.
  bool meets(const CellMask& other, int dx, int dy) const;
  void add(const CellMask& other, int dx, int dy);
  /// The highest row (then the leftmost column) at most (max_x, max_y) where
  /// `piece` meets nothing.
  std::optional<std::pair<int, int>> highest_fit(const CellMask& piece, int max_x, int max_y) const;

 private:
  std::uint64_t* row(int y) { return bits_.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(words_); }
  const std::uint64_t* row(int y) const { return bits_.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(words_); }
  struct Word {
    int row, index;
    std::uint64_t bits;
  };
  int width_, height_, words_;
  std::vector<std::uint64_t> bits_;
  std::vector<Word> taken_;  ///< a piece's non-empty words, the fullest first (meets tests these)
};

}  // namespace phedra::sheets
