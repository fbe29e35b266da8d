#pragma once
// The crease pattern of a developed P-hedron with its mountain/valley
// assignment (issue 7, item 2), as SVG and as FOLD (creasePattern frame,
// edges_assignment M/V/B, edges_foldAngle). The pattern is the region between the
// first and the last profile vertex (the boundary columns of a P-hedron collapse
// onto the apexes in the developed state). Viewed from the side where (x, z)
// is right-handed (x to the right, z up): a valley folds towards the viewer,
// a mountain away; FOLD's foldAngle is positive for valleys.

#include "phedra/developed_pattern.h"
#include "phedra/sheet_page.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace phedra {

struct CreasePattern {
  std::string name;
  std::vector<Vec2> vertices;            ///< (x, z) of the flat pattern
  std::vector<Quad> faces;
  std::vector<Segment> edges;
  std::vector<char> assignment;          ///< 'M', 'V', 'F' (stays flat), 'B' (boundary)
  std::vector<double> fold_angle;        ///< degrees at the folded state t (valley > 0)
  std::vector<double> apex_heights;      ///< for the drawing: the axis and its apexes
  double t = 0.0;                        ///< the folded state of fold_angle
  double t_assignment = 0.0;             ///< the state just off the flat one that fixed the assignment
  std::size_t mountains = 0, valleys = 0;
  /// Creases whose fold angle at `t` has the sign opposite to their assignment
  /// (or an F crease no longer flat): between t_assignment and t the hinge went
  /// through the fully folded state (+-180 degrees), its panels through each
  /// other. A pattern with any is not to be written (develop refuses it).
  std::vector<std::size_t> contradicted;
};

/// The assignment from the pattern folded to `t_assignment` (just off t*, on a side
/// that folds) with the strips' fold choices; the fold angles at `t`.
CreasePattern crease_pattern(const DevelopedPattern& pattern, const std::vector<int>& fold, double t_assignment,
                             double t);

/// The crease pattern drawn to scale on a page of its own: title, legend
/// (mountain, valley, boundary, the axis and the apexes on it), scale bar.
struct CreaseDrawing {
  SheetPage page;
  Vec2 size;           ///< the page, mm
  double scale = 1.0;  ///< mm per model unit
};
/// `scale` in mm per model unit; unset: the pattern fills about 170 x 220 mm.
CreaseDrawing crease_drawing(const CreasePattern& pattern, std::optional<double> scale = std::nullopt);
std::string crease_svg(const CreasePattern& pattern, std::optional<double> scale = std::nullopt);
std::string crease_pdf(const CreasePattern& pattern, std::optional<double> scale = std::nullopt);
nlohmann::json crease_fold(const CreasePattern& pattern);

}  // namespace phedra
