// Thick plates on cut sheets (cut_sheets.h, PlateCut): each single-panel piece
// becomes the outline a cutter follows, and the assembly page says which
// piece is hinged to which.

#include "cut_sheet_parts.h"

#include "phedra/number_format.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace phedra::sheets {
namespace {

/// The plate's face (frame xy, model units) on the sheet: the rigid motion (and
/// scale) that puts its bottom corners onto the piece's outline, over the cyclic
/// correspondence that fits best.
Polygon2 on_sheet(const std::vector<Vec3>& bottom, const std::vector<Vec3>& face, const Polygon2& outline, double scale) {
  const std::size_t n = bottom.size();
  double best = std::numeric_limits<double>::infinity();
  Polygon2 out;
  for (std::size_t shift = 0; shift < n && outline.size() == n; ++shift) {
    // 2D Kabsch: rotation from the bottom's corners (scaled) to the outline's.
    Vec2 cb = Vec2::Zero(), co = Vec2::Zero();
    for (std::size_t i = 0; i < n; ++i) {
      cb += scale * bottom[(i + shift) % n].head<2>();
      co += outline[i];
    }
    cb /= static_cast<double>(n);
    co /= static_cast<double>(n);
    double c = 0.0, s = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 a = scale * bottom[(i + shift) % n].head<2>() - cb, b = outline[i] - co;
      c += a.dot(b);
      s += a.x() * b.y() - a.y() * b.x();
    }
    const double angle = std::atan2(s, c);
    const Eigen::Matrix2d r = Eigen::Rotation2Dd(angle).toRotationMatrix();
    auto map = [&](const Vec3& p) { return Vec2(co + r * (scale * p.head<2>() - cb)); };
    double residual = 0.0;
    for (std::size_t i = 0; i < n; ++i) residual += (map(bottom[(i + shift) % n]) - outline[i]).squaredNorm();
    if (residual < best) {
      best = residual;
      out.clear();
      for (const Vec3& q : face) out.push_back(map(q));  // (a plate with a corner cut off has more corners)
    }
  }
  return out;
}

/// A counter-clockwise polygon grown by d (each edge moved out by d, corners where the moved edges meet).
Polygon2 grown(const Polygon2& p, double d) {
  if (d == 0.0) return p;
  const std::size_t n = p.size();
  std::vector<Vec2> normal(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 e = (p[(k + 1) % n] - p[k]).normalized();
    normal[k] = Vec2(e.y(), -e.x());  // outward for a counter-clockwise polygon
  }
  Polygon2 out(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2& a = normal[(k + n - 1) % n];
    const Vec2& b = normal[k];
    const double c = 1.0 + a.dot(b);
    out[k] = c > 1e-6 ? Vec2(p[k] + d * (a + b) / c) : Vec2(p[k] + d * b);
  }
  return out;
}

/// The outline with coincident corners (a welded boundary triangle's) once.
Polygon2 distinct(const Polygon2& p) {
  Polygon2 out;
  for (const Vec2& c : p) {
    if (out.empty() || (c - out.back()).norm() > 1e-9) out.push_back(c);
  }
  if (out.size() > 1 && (out.front() - out.back()).norm() <= 1e-9) out.pop_back();
  return out;
}

}  // namespace

void cut_plates(std::vector<Piece>& pieces, const ThickPlates& plates, double scale, double kerf_mm) {
  std::map<std::size_t, std::size_t> plate_of;  // panel -> plate
  for (std::size_t k = 0; k < plates.plates(); ++k) plate_of[plates.panel(k)] = k;
  for (Piece& piece : pieces) {
    if (piece.panels.size() != 1 || !piece.cuttable) continue;
    const auto found = plate_of.find(piece.panels[0].panel);
    if (found == plate_of.end()) continue;
    const std::size_t k = found->second;
    Polygon2 outline = distinct(piece.panels[0].outline);
    if (signed_area2(outline) < 0.0) std::reverse(outline.begin(), outline.end());
    const Polygon2 top = on_sheet(plates.panel_corners(k), plates.top(k), outline, scale);
    if (top.size() < 3) continue;
    piece.cut = grown(top, 0.5 * kerf_mm);
    // Labels inside the top face: the seams along their hinge edges (matched to
    // the outline's edge by direction), then the piece's name. On a small plate
    // they share the room: one cap for the seam labels, the one that makes the
    // smallest label (the name too, which a maker looks for first) largest.
    const Polygon2& panel_outline = piece.panels[0].outline;
    std::vector<std::pair<std::string, std::size_t>> seams;  // text, edge of the top face
    for (const SeamSide& side : piece.seams) {
      const Vec2 a = panel_outline[side.edge], b = panel_outline[(side.edge + 1) % panel_outline.size()];
      std::size_t edge = 0;
      double nearest = std::numeric_limits<double>::infinity();
      for (std::size_t e = 0; e < top.size(); ++e) {
        const Vec2 mid = 0.5 * (top[e] + top[(e + 1) % top.size()]);
        const Vec2 d = (top[(e + 1) % top.size()] - top[e]).normalized();
        const double off = std::abs(cross(b - a, mid - a)) / std::max((b - a).norm(), 1e-300) +
                           (1.0 - std::abs(d.dot((b - a).normalized())));
        if (off < nearest) nearest = off, edge = e;
      }
      seams.push_back({"S" + std::to_string(side.seam), edge});
    }
    const std::string name = std::to_string(piece.number) + " P" + std::to_string(piece.panels[0].panel);
    std::pair<std::size_t, double> best_score{0, -1.0};
    bool first = true;
    for (double cap : {2.6, 2.3, readable_label_mm}) {
      std::vector<SheetText> labels;
      std::vector<Box2> taken;
      double smallest = std::numeric_limits<double>::infinity();
      for (const auto& [text, edge] : seams) {
        const std::optional<Box2> box = fit_label(top, edge, text, cap, taken);
        smallest = std::min(smallest, box ? box->height : 0.0);
        if (box) taken.push_back(*box);
        labels.push_back(SheetText{text, box ? *box : no_room(seam_anchor(top, edge)), TextRole::seam});
      }
      const std::optional<Box2> box = fit_label(top, std::nullopt, name, 3.5, taken);
      smallest = std::min(smallest, box ? box->height : 0.0);
      labels.push_back(SheetText{name, box ? *box : no_room(panel_anchor(top)), TextRole::panel});
      const std::pair<std::size_t, double> score{readable_inside(labels), smallest};
      if (first || score.first > best_score.first || (score.first == best_score.first && score.second > best_score.second + 1e-9)) {
        best_score = score, piece.labels = std::move(labels), first = false;
      }
      if (smallest >= cap - 1e-9) break;  // every label at least the cap: a lower cap cannot do better
    }
    call_out_small_labels(piece);
  }
}

namespace {

/// `text` broken at its spaces into lines no wider than `room` at capital
/// height h (a word longer than that alone on its line), each line after the
/// first starting with `indent`.
std::vector<std::string> wrapped(const std::string& text, double h, double room, const std::string& indent) {
  std::vector<std::string> lines;
  std::string line;
  std::size_t from = 0;
  while (from < text.size()) {
    std::size_t space = text.find(' ', from + 1);
    if (space == std::string::npos) space = text.size();
    const std::string word = text.substr(from, space - from);
    if (!line.empty() && line != indent && text_width(line + word, h) > room) {
      lines.push_back(line);
      line = indent + word.substr(word.front() == ' ' ? 1 : 0);
    } else {
      line += word;
    }
    from = space;
  }
  lines.push_back(line);
  return lines;
}

}  // namespace

std::vector<SheetPage> assembly_pages(const CutSheets& s) {
  // Seam -> the pieces on its sides.
  std::map<std::size_t, std::vector<std::size_t>> sides;
  for (std::size_t p = 0; p < s.pieces.size(); ++p) {
    for (const SeamSide& side : s.pieces[p].seams) sides[side.seam].push_back(p);
  }
  const double m = 10.0, top = s.page.y() - m, h = 2.2, pitch = 3.4;
  // A step a piece: the earlier pieces it joins, each with its seams ("1 (S1, S3), 4 (S9)"),
  // wrapped at a comma onto indented lines when wider than the page.
  std::vector<std::string> steps;
  for (std::size_t p = 0; p < s.pieces.size(); ++p) {
    const Piece& piece = s.pieces[p];
    std::map<std::size_t, std::vector<std::size_t>> joined;  // earlier piece's number -> seams
    for (const SeamSide& side : piece.seams) {
      for (std::size_t q : sides[side.seam]) {
        if (q >= p) continue;
        std::vector<std::size_t>& seams = joined[s.pieces[q].number];
        if (std::find(seams.begin(), seams.end(), side.seam) == seams.end()) seams.push_back(side.seam);
      }
    }
    // A plate: its panel; a card piece: its panels' count (the sheet labels each).
    const std::string what = s.thick ? "P" + std::to_string(piece.panels.front().panel)
                                     : std::to_string(piece.panels.size()) + (piece.panels.size() == 1 ? " panel" : " panels");
    std::vector<std::string> parts;
    for (const auto& [number, seams] : joined) {
      // Runs of three or more consecutive seams as a range: S28-S36.
      std::vector<std::size_t> sorted = seams;
      std::sort(sorted.begin(), sorted.end());
      std::string part = std::to_string(number) + " (";
      for (std::size_t k = 0; k < sorted.size();) {
        std::size_t end = k;
        while (end + 1 < sorted.size() && sorted[end + 1] == sorted[end] + 1) ++end;
        part += (k ? ", S" : "S") + std::to_string(sorted[k]);
        if (end >= k + 2) {
          part += "-S" + std::to_string(sorted[end]);
          k = end + 1;
        } else {
          ++k;
        }
      }
      parts.push_back(part + ")");
    }
    // A card piece's panel count in brackets: "1 (4 panels)" (SVG and PDF collapse
    // the spaces of "1  4 panels", which then read as 14).
    std::string text = std::to_string(piece.number) + (s.thick ? "  " + what : " (" + what + ")") + ", page " +
                       std::to_string(s.piece_page[p] + 1) + ": " +
                       (parts.empty() ? "start here" : s.thick ? "hinge to " : "glue to ");
    for (std::size_t k = 0; k < parts.size(); ++k) text += (k ? ", " : "") + parts[k];
    // Wrapped at spaces (after the piece's number) onto indented lines.
    for (std::string& line : wrapped(text, h, s.page.x() - 2.0 * m, "     ")) steps.push_back(std::move(line));
  }
  double column_width = 40.0;
  for (const std::string& step : steps) column_width = std::max(column_width, text_width(step, h) + 5.0);
  const std::size_t columns = std::max<std::size_t>(1, static_cast<std::size_t>((s.page.x() - 2.0 * m) / column_width));
  std::vector<SheetPage> pages;
  std::size_t k = 0;
  while (k < steps.size() || pages.empty()) {
    SheetPage page;
    add_text(page, s.name + " - assembly" + (pages.empty() ? "" : " (continued)"), Vec2(m, top - 4.0), 4.0, TextRole::title);
    double y = top - 11.0;
    if (pages.empty()) {
      const std::string face = s.thick && s.thick->side == PlateSide::back ? "printed" : "unprinted";
      // Paragraphs, each wrapped at the page's width.
      const std::vector<std::string> paragraphs =
          s.thick ? std::vector<std::string>{
                        "Plates " + sheet_number(s.thickness_mm) + " mm thick, " + std::to_string(s.pieces.size()) +
                            " pieces; cut on the solid lines (kerf " + sheet_number(s.kerf_mm) + " mm allowed for).",
                        "Lay each plate with the side shown on the sheet up. The dashed purple lines are the hinge lines: "
                        "hinges go on the " + face + " face (the panels' side), across the gap between two plates, centred "
                        "on the hinge line. S3 meets S3.",
                        "Join the pieces in this order (a piece: its number, its panel, its page; then the earlier pieces it is hinged to):"}
                  : std::vector<std::string>{
                        "Card, " + std::to_string(s.pieces.size()) + " pieces: cut on the solid lines, fold on the others "
                        "(the key on sheet 1 shows mountain and valley folds as seen on the printed side), then glue each "
                        "seam (S3 meets S3): its tab under the other side's edge (a seam with no tab: tape). The views after "
                        "this list show where each piece goes.",
                        "Join the pieces in this order (a piece: its number, its panels, its page; then the earlier pieces it "
                        "is glued to):"};
      for (const std::string& paragraph : paragraphs) {
        for (const std::string& line : wrapped(paragraph, h, s.page.x() - 2.0 * m, "")) {
          add_text(page, line, Vec2(m, y), h, TextRole::note);
          y -= pitch + 0.6;
        }
        y -= 1.0;  // between paragraphs
      }
      y -= 1.0;
    }
    const double first_y = y;
    const std::size_t rows = static_cast<std::size_t>(std::max(1.0, std::floor((first_y - m) / pitch)));
    for (std::size_t c = 0; c < columns && k < steps.size(); ++c) {
      for (std::size_t r = 0; r < rows && k < steps.size(); ++r, ++k) {
        add_text(page, steps[k], Vec2(m + static_cast<double>(c) * column_width, first_y - static_cast<double>(r) * pitch), h,
                 TextRole::legend);
      }
    }
    pages.push_back(std::move(page));
    if (steps.empty()) break;
  }
  return pages;
}

}  // namespace phedra::sheets
