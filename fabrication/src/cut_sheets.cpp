// Cut sheets (cut_sheets.h): pieces laid out in assembly order on pages, with a
// title, a legend and a scale bar on every page.

#include "phedra/cut_sheets.h"

#include "cut_sheet_parts.h"
#include "phedra/errors.h"
#include "phedra/number_format.h"
#include "phedra/panel_size.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <regex>
#include <tuple>

namespace phedra {
namespace {

constexpr double footer_mm = 6.0;

/// A rigid motion of the sheet: p -> origin + s * axis + t * up for p's coordinates (s, t) in `from`.
struct Placement {
  Box2 from;      ///< the piece's box in piece coordinates
  bool turn = false;
  bool half_turn = false;  ///< then turned by 180 degrees in its box
  Vec2 corner;    ///< the page position of the placed box's lower-left corner
  Vec2 map(const Vec2& p) const {
    const Vec2 d = p - from.origin;
    const double s = d.dot(from.axis), t = d.dot(from.up());
    const Vec2 q = turn ? Vec2(from.height - t, s) : Vec2(s, t);
    return corner + (half_turn ? Vec2(size() - q) : q);
  }
  Vec2 map_direction(const Vec2& v) const {
    const double s = v.dot(from.axis), t = v.dot(from.up());
    const Vec2 q = turn ? Vec2(-t, s) : Vec2(s, t);
    return half_turn ? Vec2(-q) : q;
  }
  Vec2 size() const { return turn ? Vec2(from.height, from.width) : Vec2(from.width, from.height); }
};

/// The piece's smallest box, long side across the page when it fits that way;
/// when its smallest box fits neither way (its tabs made it wider), any
/// direction that fits: a hull edge's, or one of 360 half-degree steps.
Placement fitting_points(const std::vector<Vec2>& points, const Box2& content) {
  auto fits = [&](const Placement& p) { return p.size().x() <= content.width + 1e-9 && p.size().y() <= content.height + 1e-9; };
  auto try_box = [&](const Box2& box, Placement& out) {
    for (bool turn : {box.height > box.width, box.height <= box.width}) {
      out = Placement{box, turn, false, Vec2::Zero()};
      if (fits(out)) return true;
    }
    return false;
  };
  Placement out;
  const Box2 smallest = minimum_box(points);
  if (try_box(smallest, out)) return out;
  const Polygon2 hull = convex_hull(points);
  for (int k = 0; k < 360; ++k) {
    const double angle = k * M_PI / 360.0;
    const Vec2 axis(std::cos(angle), std::sin(angle)), up(-axis.y(), axis.x());
    double s0 = 1e300, s1 = -1e300, t0 = 1e300, t1 = -1e300;
    for (const Vec2& p : hull) {
      s0 = std::min(s0, p.dot(axis)), s1 = std::max(s1, p.dot(axis));
      t0 = std::min(t0, p.dot(up)), t1 = std::max(t1, p.dot(up));
    }
    if (try_box(Box2{s0 * axis + t0 * up, axis, s1 - s0, t1 - t0}, out)) return out;
  }
  throw InvalidInputError("--page", "a piece of " + format_significant(smallest.width) + " x " +
                                       format_significant(smallest.height) +
                                       " mm (its kerf included) fits the page in no direction: a larger --page, a "
                                       "smaller --scale or --model-size, or a smaller --kerf");
}

/// The piece's placement with its called-out labels; when they make it too
/// large for the page (a piece nearly a page long), they go back to 2 mm
/// labels centred where they point, and the piece is placed without them.
Placement fitting(Piece& piece, const Box2& content) {
  try {
    return fitting_points(piece.points(), content);
  } catch (const Error&) {
    bool any = false;
    for (SheetText& t : piece.labels) {
      if (!t.leader) continue;
      t.box.origin = *t.leader - 0.5 * t.box.width * t.box.axis - 0.5 * t.box.height * t.box.up();
      t.leader.reset();
      any = true;
    }
    if (!any) throw;
    return fitting_points(piece.points(), content);
  }
}

void place(Piece& piece, const Placement& at) {
  if (piece.cut) {
    for (Vec2& c : *piece.cut) c = at.map(c);
  }
  for (PiecePanel& p : piece.panels) {
    for (Vec2& c : p.outline) c = at.map(c);
  }
  for (PieceFold& f : piece.folds) f.a = at.map(f.a), f.b = at.map(f.b);
  for (SeamSide& s : piece.seams) {
    if (s.tab) {
      for (Vec2& c : *s.tab) c = at.map(c);
    }
  }
  for (SheetText& label : piece.labels) {
    label.box.origin = at.map(label.box.origin);
    label.box.axis = at.map_direction(label.box.axis);
    label.box = sheets::upright(label.box);
    if (label.leader) label.leader = at.map(*label.leader);
  }
}

/// Footer: scale bar and printing note.
void footer(SheetPage& page, const CutSheets& s, std::size_t k) {
  const double m = 10.0, right = s.page.x() - m;
  add_scale_bar(page, Vec2(m, m), s.scale, std::min(50.0, 0.3 * (right - m)));
  // Sheet 1 says where piece 1, the first to assemble, is when the nesting put it
  // later (there in the footer: the key's room is measured before the layout).
  const bool elsewhere = k == 0 && !s.piece_page.empty() && s.piece_page[0] != 0;
  const std::string note = (elsewhere ? "piece 1 is on sheet " + std::to_string(s.piece_page[0] + 1) + "; " : std::string()) +
                           "print at 100 % (actual size)";
  add_text(page, note, Vec2(right - text_width(note, 2.2), m), 2.2, TextRole::note);
}

/// Title, legend (the key on the first sheet only: later sheets keep their room
/// for pieces), scale bar and footer of page k of n; returns the height
/// (from the page's top) the title and legend take.
double decorate(SheetPage& page, const CutSheets& s, std::size_t k, bool any_uncuttable, bool any_flat,
                bool any_seam_on_fold, std::size_t left_out) {
  const double m = 10.0, top = s.page.y() - m, right = s.page.x() - m;
  add_text(page, s.name + " - cut sheet " + std::to_string(k + 1) + " of " + std::to_string(s.pages.size()) + " (" +
                     (s.thick ? std::string("plates") : to_string(s.mode)) + ")",
           Vec2(m, top - 4.0), 4.0, TextRole::title);
  Legend legend(page, m, right, top - 11.0);
  if (k > 0) {
    legend.note("the key to the lines and labels is on sheet 1");
    footer(page, s, k);
    return s.page.y() - legend.bottom();
  }
  if (s.thick) {
    legend.line(LineStyle::cut, "cut (" + sheet_number(s.kerf_mm) + " mm kerf allowed for: half of it outside)");
    legend.line(LineStyle::hinge, "hinge line (the panel's edge)");
    legend.sample("S1", TextRole::seam, "hinge to the other S1");
    legend.sample("12 P7", TextRole::panel, "piece 12 in assembly order, panel 7 of the 3D files");
    legend.note("plates " + sheet_number(s.thickness_mm) + " mm thick, straight cuts inside the bevelled plates; "
                "assembly (order, views) on the last pages");
    for (const std::string& words : plates_fold_words(s)) legend.warning(words);
    footer(page, s, k);
    return s.page.y() - legend.bottom();
  }
  legend.line(LineStyle::cut, "cut");
  legend.line(LineStyle::mountain, "mountain fold (away from you)");
  legend.line(LineStyle::valley, "valley fold (towards you)");
  if (any_flat) legend.line(LineStyle::flat, "flat hinge (crease it)");
  legend.line(LineStyle::tab_fold, "tab fold");
  legend.fill(FillStyle::swatch_tab, "glue tab");
  legend.sample("S1", TextRole::seam, "glue to the other S1");
  if (any_seam_on_fold) legend.sample("S2", TextRole::seam, "by a fold: glue the other S2 onto it");
  legend.sample("P7", TextRole::panel, s.mode == PieceMode::cells ? "panel 7 (a wall: glue its two copies face to face)"
                                                                   : "panel 7 (as numbered in the 3D files)");
  if (any_uncuttable) legend.fill(FillStyle::swatch_not_cuttable, "not one plate (see phedra check)");
  if (left_out > 0) {
    legend.note(std::to_string(left_out) + (left_out == 1 ? " panel is" : " panels are") +
                " not on the sheets: oversized or slivers, nothing one can cut (see phedra check)");
  }
  legend.sample("12 P3", TextRole::panel, "piece 12 in assembly order, on its first panel");
  legend.note(std::string("pieces numbered in assembly order, ") + (s.mode == PieceMode::columns ? "column by column" : "row by row") +
              "; nested to save paper");
  footer(page, s, k);
  return s.page.y() - legend.bottom();
}

}  // namespace

PieceMode piece_mode_from_string(const std::string& name) {
  for (PieceMode mode : {PieceMode::strips, PieceMode::columns, PieceMode::cells, PieceMode::panels}) {
    if (to_string(mode) == name) return mode;
  }
  throw InvalidInputError("--pieces", "unknown piece mode \"" + name + "\" (use strips, columns, cells or panels)");
}

std::string to_string(PieceMode mode) {
  switch (mode) {
    case PieceMode::strips: return "strips";
    case PieceMode::columns: return "columns";
    case PieceMode::cells: return "cells";
    case PieceMode::panels: return "panels";
  }
  return "?";
}

Vec2 page_size_from_string(const std::string& name) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (lower == "a4") return {210.0, 297.0};
  if (lower == "a3") return {297.0, 420.0};
  if (lower == "letter") return {215.9, 279.4};
  std::smatch match;
  static const std::regex custom(R"(^\s*([0-9]+(?:\.[0-9]*)?)\s*x\s*([0-9]+(?:\.[0-9]*)?)\s*$)");
  if (std::regex_match(lower, match, custom)) {
    const Vec2 size(std::stod(match[1]), std::stod(match[2]));
    if (size.minCoeff() < 100.0 || size.maxCoeff() > 5000.0) {
      throw InvalidInputError("--page", "\"" + name + "\": each side must lie in [100, 5000] mm");
    }
    return size;
  }
  throw InvalidInputError("--page", "unknown page size \"" + name + "\" (use a4, letter, a3 or WxH in mm, e.g. 300x200)");
}

std::vector<std::string> plates_fold_words(const CutSheets& s) {
  if (!s.thick || !s.hardly_fold) return {};
  return plates_fold_words(*s.thick, s.thickness_mm, s.scale, " mm", s.folding);
}

std::vector<std::string> plates_fold_words(const ThickReport& r, double thickness, double scale, const std::string& unit,
                                           const std::optional<ThickFolding>& folding) {
  const double f = thick_fraction(r);
  if (f >= 0.1) return {};
  const std::string these = "these " + format_significant(thickness) + unit + " plates ";
  std::vector<std::string> out;
  if (r.at_t_star) {
    out.push_back(these + "cannot fold: they collide at t*");
  } else if (f < 1e-6) {
    out.push_back(these + "cannot fold: they cannot move from t* (" + format_significant(r.t_star) + ")");
  } else {
    out.push_back(these + "can hardly fold: they move over " + format_significant(100.0 * f, 2) + " % of the flexion interval only");
  }
  if (folding) {
    // Three significant digits, rounded down: the thickness suggested must fold as said.
    const double x = folding->thickness * scale, step = std::pow(10.0, std::floor(std::log10(x)) - 2.0);
    const std::string t = format_significant(std::floor(x / step) * step, 3);
    out.push_back("plates up to " + t + unit + " thick on the " + to_string(folding->side) + " side fold over half of it (" +
                  (unit.empty() ? "--thickness " : "--thickness-mm ") + t + " --plate-side " + to_string(folding->side) + ")");
  } else {
    out.push_back("no plates fold over half of it, however thin (down to 1e-4 of the model size)");
  }
  return out;
}

std::vector<SheetLine> Piece::lines() const {
  std::vector<SheetLine> out;
  if (cut) {  // a plate: its cut outline, and the panel's hinge edges
    for (std::size_t k = 0; k < cut->size(); ++k) out.push_back(SheetLine{(*cut)[k], (*cut)[(k + 1) % cut->size()], LineStyle::cut});
    for (const SeamSide& s : seams) {
      const Polygon2& o = panels[s.panel].outline;
      out.push_back(SheetLine{o[s.edge], o[(s.edge + 1) % o.size()], LineStyle::hinge});
    }
    return out;
  }
  std::vector<std::vector<bool>> fold(panels.size());
  for (std::size_t i = 0; i < panels.size(); ++i) fold[i].assign(panels[i].outline.size(), false);
  for (const PieceFold& f : folds) {
    out.push_back(SheetLine{f.a, f.b, f.style});
    for (std::size_t i : {f.first, f.second}) {
      const Polygon2& o = panels[i].outline;
      for (std::size_t k = 0; k < o.size(); ++k) {
        const Vec2 &p = o[k], &q = o[(k + 1) % o.size()];
        if (((p - f.a).norm() < 1e-6 && (q - f.b).norm() < 1e-6) || ((p - f.b).norm() < 1e-6 && (q - f.a).norm() < 1e-6)) {
          fold[i][k] = true;
        }
      }
    }
  }
  for (const SeamSide& s : seams) {
    if (!s.tab) continue;
    fold[s.panel][s.edge] = true;
    const Polygon2& t = *s.tab;  // a, b, then the tab's outer corners
    out.push_back(SheetLine{t[0], t[1], LineStyle::tab_fold});
    for (std::size_t k = 1; k < t.size(); ++k) out.push_back(SheetLine{t[k], t[(k + 1) % t.size()], LineStyle::cut});
  }
  for (std::size_t i = 0; i < panels.size(); ++i) {
    const Polygon2& o = panels[i].outline;
    for (std::size_t k = 0; k < o.size(); ++k) {
      if (!fold[i][k]) out.push_back(SheetLine{o[k], o[(k + 1) % o.size()], LineStyle::cut});
    }
  }
  return out;
}

std::vector<SheetFill> Piece::fills() const {
  std::vector<SheetFill> out;
  for (const SeamSide& s : seams) {
    if (s.tab) out.push_back(SheetFill{*s.tab, FillStyle::tab, std::nullopt});
  }
  if (!cuttable) {
    for (const PiecePanel& p : panels) out.push_back(SheetFill{p.outline, FillStyle::not_cuttable, p.panel});
  }
  return out;
}

/// What a piece covers on its page: panels (their hulls when it cannot be
/// cut), tabs, a plate's cut outline, called-out labels.
std::vector<Polygon2> piece_shapes(const Piece& piece) {
  std::vector<Polygon2> out;
  for (const PiecePanel& p : piece.panels) out.push_back(piece.cuttable ? p.outline : convex_hull(p.outline));
  for (const SeamSide& s : piece.seams) {
    if (s.tab) out.push_back(*s.tab);
  }
  if (piece.cut) out.push_back(*piece.cut);
  for (const SheetText& t : piece.labels) {
    if (t.leader) out.push_back(t.box.corners());
  }
  return out;
}

std::vector<Vec2> Piece::points() const {
  std::vector<Vec2> out;
  for (const PiecePanel& p : panels) out.insert(out.end(), p.outline.begin(), p.outline.end());
  if (cut) out.insert(out.end(), cut->begin(), cut->end());
  for (const SeamSide& s : seams) {
    if (s.tab) out.insert(out.end(), s.tab->begin(), s.tab->end());
  }
  for (const SheetText& t : labels) {  // (called out beside the piece: its room on the sheet too)
    if (!t.leader) continue;
    const Polygon2 c = t.box.corners();
    out.insert(out.end(), c.begin(), c.end());
  }
  return out;
}

namespace {

/// Unfolds, labels and lays out the pieces under a header `header` mm tall.
CutSheets lay_out(const Design& design, const CutSheetOptions& options, CutSheets s, double header,
                  const ThickPlates* plates) {
  const double m = options.margin;
  s.content = Box2{Vec2(m, m + footer_mm), Vec2::UnitX(), s.page.x() - 2.0 * m, s.page.y() - 2.0 * m - header - footer_mm};
  {  // Later sheets: a title and one line above their pieces.
    CutSheets probe = s;
    probe.pages.resize(2);
    SheetPage unused;
    const double later_header = std::min(header, decorate(unused, probe, 1, false, false, false, 0) + 4.0 - m);
    s.later_content = s.content;
    s.later_content.height = s.page.y() - 2.0 * m - later_header - footer_mm;
  }
  const double tab_room = options.tabs ? 2.0 * options.max_tab_mm : 0.0;
  const Vec2 fit(s.content.width - tab_room, s.content.height - tab_room);
  s.left_out.clear();
  s.pieces = sheets::unfold_pieces(design, options, s.scale, fit, s.seams, s.left_out);
  for (std::size_t k = 0; k < s.pieces.size(); ++k) s.pieces[k].number = k + 1;
  if (plates) sheets::cut_plates(s.pieces, *plates, s.scale, s.kerf_mm);
  // Nested by their shapes (sheet_nesting.cpp), tallest first (first fit,
  // decreasing height: fewer pages; the pieces' numbers keep the assembly
  // order); each on the first page with room (of the last three), at the
  // highest, then leftmost, free place, in whichever of its
  // orientations sits highest there (long side across the page, or the other
  // way when that fits; either turned half a turn: a zigzag strip fits into
  // the previous one's notches).
  std::vector<Placement> at(s.pieces.size());
  std::vector<std::size_t> order(s.pieces.size());
  for (std::size_t k = 0; k < s.pieces.size(); ++k) {
    at[k] = fitting(s.pieces[k], s.content);
    order[k] = k;
  }
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return at[a].size().y() > at[b].size().y(); });
  constexpr double cell = 1.0;  // mm
  const double reach = 0.5 * options.gap;
  const int pad = static_cast<int>(std::ceil(reach / cell)) + 2;
  const int columns = static_cast<int>(std::floor(s.content.width / cell + 1e-9));
  auto rows = [&](std::size_t page) { return static_cast<int>(std::floor(s.content_of(page).height / cell + 1e-9)); };
  std::vector<sheets::CellMask> taken;
  s.piece_page.assign(s.pieces.size(), 0);
  auto masks_of = [&](std::size_t k, std::vector<Placement>& ways) {
    std::vector<sheets::CellMask> masks;
    for (Placement& w : ways) {
      w.corner = Vec2::Zero();
      std::vector<Polygon2> shapes = piece_shapes(s.pieces[k]);
      for (Polygon2& shape : shapes) {
        for (Vec2& p : shape) p = w.map(p);
      }
      masks.push_back(sheets::CellMask::of_shapes(shapes, w.size(), cell, reach, pad));
    }
    return masks;
  };
  // The highest (then leftmost) place on `page` of any of the ways: (way, x, y).
  auto best_on = [&](std::size_t page, const std::vector<Placement>& ways, const std::vector<sheets::CellMask>& masks) {
    std::optional<std::tuple<std::size_t, int, int>> best;
    for (std::size_t w = 0; w < ways.size(); ++w) {
      const int max_x = static_cast<int>(std::floor((s.content.width - ways[w].size().x()) / cell + 1e-9));
      const int max_y = static_cast<int>(std::floor((s.content_of(page).height - ways[w].size().y()) / cell + 1e-9));
      if (max_x < 0 || max_y < 0) continue;
      const auto found = taken[page].highest_fit(masks[w], max_x, max_y);
      if (found && (!best || found->second > std::get<2>(*best) || (found->second == std::get<2>(*best) && found->first < std::get<1>(*best)))) {
        best = std::tuple{w, found->first, found->second};
      }
    }
    return best;
  };
  // Each piece's ways (orientations) and their masks, once: the nesting may run twice.
  std::vector<std::vector<Placement>> ways_of(s.pieces.size());
  std::vector<std::vector<sheets::CellMask>> masks_of_piece(s.pieces.size());
  for (std::size_t k = 0; k < s.pieces.size(); ++k) {
    for (const bool other_turn : {false, true}) {
      Placement w = at[k];
      if (other_turn) {
        w.turn = !w.turn;
        if (w.size().x() > s.content.width + 1e-9 || w.size().y() > s.content.height + 1e-9) continue;
      }
      for (const bool half : {false, true}) {
        w.half_turn = half;
        ways_of[k].push_back(w);
      }
    }
    masks_of_piece[k] = masks_of(k, ways_of[k]);
  }
  struct Spot {
    std::size_t page = 0, way = 0;
    int x = 0, y = 0;
  };
  // Every piece in `sequence` on the first page with room (of the last few): where each goes.
  auto nest = [&](const std::vector<std::size_t>& sequence) {
    taken.clear();
    std::vector<Spot> spots(s.pieces.size());
    for (const std::size_t k : sequence) {
      // The last few pages only: earlier ones are full (and each page tried costs a scan).
      constexpr std::size_t open_pages = 3;
      for (std::size_t page = taken.size() > open_pages ? taken.size() - open_pages : 0;; ++page) {
        const bool fresh = page == taken.size();
        if (fresh) taken.emplace_back(columns + 2 * pad, rows(page) + 2 * pad);
        const auto best = best_on(page, ways_of[k], masks_of_piece[k]);
        if (!best) {
          if (fresh) throw Error(ExitCode::internal, "piece " + std::to_string(k + 1) + " fits no empty page");
          continue;
        }
        const auto [way, x, y] = *best;
        taken[page].add(masks_of_piece[k][way], x, y);
        spots[k] = Spot{page, way, x, y};
        break;
      }
    }
    return spots;
  };
  std::vector<Spot> spots = nest(order);
  std::size_t pages = taken.size();
  // A last page that holds little (under a third of a page of the pieces' boxes):
  // once more with its pieces first, the hardest to place, so that the others
  // fill the room around them (grid-3x3: one piece on a third page).
  if (pages > 1) {
    double last_area = 0.0;
    std::vector<std::size_t> again;
    for (const std::size_t k : order) {
      if (spots[k].page + 1 != pages) continue;
      last_area += ways_of[k].front().size().prod();
      again.push_back(k);
    }
    if (last_area < s.later_content.width * s.later_content.height / 3.0) {
      for (const std::size_t k : order) {
        if (spots[k].page + 1 != pages) again.push_back(k);
      }
      std::vector<Spot> other = nest(again);
      if (taken.size() < pages) {
        spots = std::move(other);
        pages = taken.size();
      }
    }
  }
  // Piece 1, the first to assemble, on sheet 1: its page swapped with the first
  // when its pieces fit below the first page's key (the pieces sit at the top of
  // a page: they move down by the key's extra height, the first page's up), else
  // the nesting once more with it first, kept when that takes no page more.
  if (!s.pieces.empty() && spots[0].page != 0) {
    const std::size_t p = spots[0].page;
    const double extra = (s.later_content.height - s.content.height) / cell;
    const int down = static_cast<int>(std::ceil(extra - 1e-9)), up = static_cast<int>(std::floor(extra + 1e-9));
    bool fits = true;
    for (std::size_t k = 0; k < s.pieces.size(); ++k) fits = fits && (spots[k].page != p || spots[k].y >= down);
    if (fits) {
      for (Spot& spot : spots) {
        if (spot.page == p) {
          spot.page = 0, spot.y -= down;
        } else if (spot.page == 0) {
          spot.page = p, spot.y += up;
        }
      }
    }
  }
  if (!s.pieces.empty() && spots[0].page != 0) {
    std::vector<std::size_t> first{0};
    for (const std::size_t k : order) {
      if (k != 0) first.push_back(k);
    }
    std::vector<Spot> other = nest(first);
    if (taken.size() <= pages) {
      spots = std::move(other);
      pages = taken.size();
    }
  }
  for (std::size_t k = 0; k < s.pieces.size(); ++k) {
    Placement w = ways_of[k][spots[k].way];
    w.corner = s.content_of(spots[k].page).origin + cell * Vec2(spots[k].x, spots[k].y);
    place(s.pieces[k], w);
    s.piece_page[k] = spots[k].page;
  }
  s.pages.resize(s.pieces.empty() ? 1 : pages);
  bool& any_uncuttable = s.any_uncuttable;
  bool& any_flat = s.any_flat;
  bool& any_seam_on_fold = s.any_seam_on_fold;
  s.smallest_label = std::numeric_limits<double>::infinity();
  for (std::size_t p = 0; p < s.pieces.size(); ++p) {
    const Piece& piece = s.pieces[p];
    SheetPage& out = s.pages[s.piece_page[p]];
    out.pieces.push_back(p);
    for (const SheetLine& l : piece.lines()) out.lines.push_back(l);
    for (const SheetFill& f : piece.fills()) out.fills.push_back(f);
    for (const SheetText& t : piece.labels) {
      out.texts.push_back(t);
      s.smallest_label = std::min(s.smallest_label, t.box.height);
      if (!t.leader) continue;
      // A called-out label: a leader from a dot on the point it names to the label.
      out.lines.push_back(SheetLine{*t.leader, nearest_point(t.box, *t.leader), LineStyle::leader});
      const double r = 0.35;
      out.fills.push_back(SheetFill{Polygon2{*t.leader + Vec2(-r, -r), *t.leader + Vec2(r, -r), *t.leader + Vec2(r, r), *t.leader + Vec2(-r, r)},
                                    FillStyle::marker, std::nullopt});
      ++s.called_out;
    }
    any_uncuttable = any_uncuttable || !piece.cuttable;
    s.folds += piece.folds.size();
    for (const PieceFold& f : piece.folds) any_flat = any_flat || f.style == LineStyle::flat;
    for (const SeamSide& side : piece.seams) any_seam_on_fold = any_seam_on_fold || side.on_fold;
    for (const SeamSide& side : piece.seams) s.tabs += side.tab ? 1 : 0;
  }
  if (!std::isfinite(s.smallest_label)) s.smallest_label = 0.0;
  s.untabbed_seams = options.tabs ? s.seams - s.tabs : 0;
  for (std::size_t k = 0; k < s.pages.size(); ++k) decorate(s.pages[k], s, k, any_uncuttable, any_flat, any_seam_on_fold, s.left_out.size());
  s.piece_pages = s.pages.size();
  if (plates) {
    s.cut_area_mm2 = 0.0;
    for (const Piece& piece : s.pieces) {
      if (piece.cut) s.cut_area_mm2 += 0.5 * std::abs(signed_area2(*piece.cut));
    }
  }
  // The assembly: the order in words, then views of it as it grows (plates and card alike).
  for (SheetPage& assembly : sheets::assembly_pages(s)) s.pages.push_back(std::move(assembly));
  const AssemblyMesh& mesh = plates ? plates->mesh() : panel_mesh(design);
  const Points x = plates ? plates->positions(design.assembly.t_star()) : mesh.positions(design.assembly.evaluate(design.assembly.t_star()));
  for (SheetPage& views : sheets::assembly_views(s, mesh, x)) s.pages.push_back(std::move(views));
  for (const SheetPage& pg : s.pages) {
    for (const SheetLine& l : pg.lines) {
      if (!l.a.allFinite() || !l.b.allFinite()) throw Error(ExitCode::internal, "a cut-sheet line is not finite");
    }
  }
  return s;
}

CutSheets lay_out_with_header(const Design& design, const CutSheetOptions& options, const CutSheets& base,
                              const ThickPlates* plates) {
  const double m = options.margin;
  // The header as tall as the legend needs on this page width, and a 4 mm gap:
  // first with every item (the flags are known once the pieces are), then, when
  // the items shown need fewer rows, again with the room that frees.
  auto header_for = [&](bool uncuttable, bool flat, bool on_fold, std::size_t left_out) {
    CutSheets probe_sheets = base;
    probe_sheets.pages.resize(1);
    SheetPage probe;
    return decorate(probe, probe_sheets, 0, uncuttable, flat, on_fold, left_out) + 4.0 - m;
  };
  auto flags_header = [&](const CutSheets& s) {
    return header_for(s.any_uncuttable, s.any_flat, s.any_seam_on_fold, s.left_out.size());
  };
  const double worst = header_for(true, true, true, 999999);
  CutSheets first = lay_out(design, options, base, worst, plates);
  const double tight = flags_header(first);
  if (tight < worst - 0.5) {
    CutSheets again = lay_out(design, options, base, tight, plates);
    if (flags_header(again) <= tight + 1e-9) return again;
  }
  return first;
}

}  // namespace

CutSheets cut_sheets(const Design& design, const CutSheetOptions& options) {
  const Assembly& a = design.assembly;
  if (options.scale && !(*options.scale > 0.0 && std::isfinite(*options.scale))) {
    throw InvalidInputError("--scale", "must be a positive number of millimetres per model unit");
  }
  if (!(options.tab_depth > 0.0 && options.tab_depth < 0.5)) {
    throw InvalidInputError("--tab-depth", "must lie in (0, 0.5) of the seam's length");
  }
  CutSheets base;
  base.name = a.name();
  base.mode = options.mode;
  base.page = options.page;
  // The size of the panels that go on the sheets (an oversized panel's 1e8 would make every piece a speck).
  base.scale = options.scale ? *options.scale : options.model_mm / bounded_model_size(design);
  if (const double across = base.scale * bounded_model_size(design); !(across <= 1e7)) {
    throw InvalidInputError(options.scale ? "--scale" : "--model-size",
                            "the model would be " + format_significant(across) + " mm across on the sheets: more "
                            "than 10 km (a smaller " + std::string(options.scale ? "--scale" : "--model-size") + ")");
  }
  if (options.plates) {
    const PlateCut& cut = *options.plates;
    if (!(cut.thickness_mm > 0.0) || !std::isfinite(cut.thickness_mm)) {
      throw InvalidInputError("--thickness-mm", "must be a positive number of millimetres");
    }
    if (!(cut.kerf_mm >= 0.0) || !std::isfinite(cut.kerf_mm)) throw InvalidInputError("--kerf", "must be a number of millimetres >= 0");
    CutSheetOptions plate_options = options;
    plate_options.plates.reset();
    plate_options.mode = PieceMode::panels;  // one piece a plate
    plate_options.tabs = false;
    ThickOptions thick;
    thick.thickness = cut.thickness_mm / base.scale;
    thick.millimetres_per_unit = base.scale;
    thick.side = cut.side;
    base.mode = PieceMode::panels;
    const BuildabilityReport thin = assess_buildability(design);
    base.thick = check_thickness(design, thin, thick);
    // Plates that hardly fold: the thickest that fold over half the interval, to suggest.
    if (thick_fraction(*base.thick) < 0.1) {
      base.hardly_fold = true;
      base.folding = thickest_folding(design, thin, thick, 0.5);
    }
    base.kerf_mm = cut.kerf_mm;
    base.thickness_mm = cut.thickness_mm;
    const ThickPlates plates = thick_plates(design, *base.thick);
    return lay_out_with_header(design, plate_options, base, &plates);
  }
  return lay_out_with_header(design, options, base, nullptr);
}

}  // namespace phedra
