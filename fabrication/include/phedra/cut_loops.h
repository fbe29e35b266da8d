#pragma once
// The cut lines of a sheet page as a cutter follows them: closed loops, chained
// from the segments the page draws (each piece's outline, its tabs' sides), the
// inner ones first (a hole is cut before the piece around it falls out).

#include "phedra/sheet_geometry.h"
#include "phedra/sheet_page.h"

#include <vector>

namespace phedra {

struct CutLoops {
  std::vector<Polygon2> closed;         ///< inner before outer: by area, smallest first
  std::vector<std::vector<Vec2>> open;  ///< chains that do not close (none on phedra's sheets)
};

/// The page's cut segments (LineStyle::cut, not the key's samples) joined end
/// to end where their ends lie within `tolerance` (mm); collinear runs stay
/// as they are drawn.
CutLoops cut_loops(const std::vector<SheetLine>& lines, double tolerance = 1e-6);

}  // namespace phedra
