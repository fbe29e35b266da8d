// Unfolding a design into connected pieces (cut_sheets.h): a greedy unfolder
// that joins panels across hinges in the preferred order of the piece mode and
// refuses a panel that would overlap the piece or outgrow the page.

#include "cut_sheet_parts.h"

#include "phedra/assembly_mesh.h"
#include "phedra/errors.h"
#include "phedra/fold_angle.h"
#include "phedra/number_format.h"
#include "phedra/panel_size.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <tuple>

namespace phedra::sheets {
namespace {

/// Overlaps up to this (mm) are contact (shared edges and corners, rounding).
constexpr double contact_mm = 1e-6;
/// Panels are joined in a piece only across a fold at least this long (mm).
constexpr double shortest_fold_mm = 1.0;

struct Face {
  std::size_t panel = 0, member = 0, row = 0, column = 0;
  std::vector<std::size_t> corners;  ///< distinct mesh vertices, counter-clockwise about the normal
  PanelShape shape = PanelShape::convex;
  Vec3 normal = Vec3::Zero();
};

/// One side of a mesh edge: face f's edge from corner k to k + 1.
struct Side {
  std::size_t face = 0, edge = 0;
};

struct Mesh {
  std::vector<Face> faces;
  Points x;                                          ///< at t*, model units
  std::map<std::tuple<std::size_t, std::size_t, std::size_t>, std::vector<Side>> edges;  ///< (group, lo, hi)
  std::tuple<std::size_t, std::size_t, std::size_t> key(const Face& f, std::size_t k, bool cells) const {
    const std::size_t u = f.corners[k], v = f.corners[(k + 1) % f.corners.size()];
    return {cells ? f.member : 0, std::min(u, v), std::max(u, v)};
  }
};

Mesh build_mesh(const Design& design, PieceMode mode) {
  const Assembly& a = design.assembly;
  const AssemblyMesh panels = panel_mesh(design);
  const bool cells = mode == PieceMode::cells;
  if (cells && design.merge) {
    throw InvalidInputError("--pieces", "cells: this design merges its cells into one tube (\"merge\": true), so it "
                                        "has no walls to glue cell to cell; use strips, columns or panels");
  }
  const AssemblyMesh mesh = cells ? separate_mesh(a) : panels;
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> panel_of;  // (member, local) -> export panel
  for (std::size_t f = 0; f < panels.faces.size(); ++f) {
    panel_of[{panels.face_member[f], panels.face_local[f]}] = f;
    if (const auto& other = panels.face_shared_with[f]) panel_of[{other->member, other->local}] = f;
  }
  Mesh out;
  out.x = mesh.positions(a.evaluate(a.t_star()));
  const std::vector<Quad> welded = welded_faces(mesh, coincident_vertices(mesh, a));
  out.faces.resize(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    Face& face = out.faces[f];
    const std::size_t m = mesh.face_member[f], columns = a.topology(m).face_columns();
    face.panel = cells ? panel_of.at({m, mesh.face_local[f]}) : f;
    face.member = m;
    face.row = mesh.face_local[f] / columns;
    face.column = mesh.face_local[f] % columns;
    face.corners = distinct_corners(welded[f]);
    const Quad& q = mesh.faces[f];
    face.shape = panel_shape({out.x[q[0]], out.x[q[1]], out.x[q[2]], out.x[q[3]]});
    const auto& c = face.corners;
    face.normal = c.size() == 3 ? (out.x[c[1]] - out.x[c[0]]).cross(out.x[c[2]] - out.x[c[0]])
                                : (out.x[c[2]] - out.x[c[0]]).cross(out.x[c[3]] - out.x[c[1]]);
    if (face.normal.squaredNorm() > 0.0) face.normal.normalize();
    if (c.size() < 3) face.shape = PanelShape::degenerate;
    for (std::size_t k = 0; k < c.size(); ++k) out.edges[out.key(face, k, cells)].push_back({f, k});
  }
  // Simple panels beyond the size bounds cannot be cut either (filled red, like bow-ties).
  const std::vector<PanelProportions> size = panel_proportions(out.x, mesh.faces);
  const SizeBounds bounds;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    Face& face = out.faces[f];
    if (!is_valid_panel(face.shape)) continue;
    if (size[f].edge_ratio > bounds.max_edge_ratio) face.shape = PanelShape::oversized;
    else if (size[f].aspect < bounds.min_aspect) face.shape = PanelShape::sliver;
  }
  return out;
}

/// The face in its own plane, seen from its normal: corner 0 at the origin, edge 0 along +x (mm).
Polygon2 flat(const Mesh& mesh, const Face& face, double scale) {
  const auto& c = face.corners;
  const Vec3 origin = mesh.x[c[0]];
  Vec3 u = mesh.x[c[1]] - origin;
  Vec3 normal = face.normal;
  if (u.squaredNorm() == 0.0 || normal.squaredNorm() == 0.0) return Polygon2(c.size(), Vec2::Zero());
  u.normalize();
  const Vec3 v = normal.cross(u).normalized();
  Polygon2 out;
  for (std::size_t k : c) out.emplace_back(scale * u.dot(mesh.x[k] - origin), scale * v.dot(mesh.x[k] - origin));
  return out;
}

/// Moves `shape` rigidly so that its corners i and j land on a and b.
Polygon2 attach(Polygon2 shape, std::size_t i, std::size_t j, const Vec2& a, const Vec2& b) {
  const Vec2 from = shape[j] - shape[i], to = b - a;
  const double turn = std::atan2(to.y(), to.x()) - std::atan2(from.y(), from.x());
  const Eigen::Rotation2Dd r(turn);
  const Vec2 pivot = shape[i];
  for (Vec2& p : shape) p = a + r * (p - pivot);
  return shape;
}

bool fits(const std::vector<Vec2>& points, const Vec2& fit) {
  const Box2 box = minimum_box(points);
  const double w = box.width, h = box.height;
  return (w <= fit.x() && h <= fit.y()) || (h <= fit.x() && w <= fit.y());
}

std::string mm(double x) { return format_number(std::round(x * 10.0) / 10.0); }

class Unfolder {
 public:
  Unfolder(const Design& design, const CutSheetOptions& options, double scale, Vec2 fit)
      : mesh_(build_mesh(design, options.mode)), options_(options), scale_(scale), fit_(fit),
        cells_(options.mode == PieceMode::cells), piece_of_(mesh_.faces.size(), none),
        slot_(mesh_.faces.size(), 0), placed_(mesh_.faces.size()) {}

  std::vector<Piece> run(std::size_t& seams, std::vector<std::size_t>& left_out) {
    std::vector<std::size_t> order(mesh_.faces.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t f, std::size_t g) { return line_key(f) < line_key(g); });
    for (std::size_t seed : order) {
      if (off_the_sheets(seed)) {
        left_out.push_back(mesh_.faces[seed].panel);
      } else if (piece_of_[seed] == none) {
        grow(seed);
      }
    }
    std::sort(left_out.begin(), left_out.end());
    left_out.erase(std::unique(left_out.begin(), left_out.end()), left_out.end());
    find_folds_and_seams(seams);
    return std::move(pieces_);
  }

 private:
  static constexpr std::size_t none = static_cast<std::size_t>(-1);

  /// An oversized panel or a sliver: not a part anyone cuts (a 1e8-long panel
  /// would also set the scale of every other piece), left off the sheets.
  bool off_the_sheets(std::size_t f) const {
    return mesh_.faces[f].shape == PanelShape::oversized || mesh_.faces[f].shape == PanelShape::sliver;
  }

  /// The order pieces are started in: strips row by row (across the members of
  /// an array), columns and cells member by member.
  std::tuple<std::size_t, std::size_t, std::size_t> line_key(std::size_t f) const {
    const Face& face = mesh_.faces[f];
    switch (options_.mode) {
      case PieceMode::strips: return {face.row, face.member, face.column};
      case PieceMode::columns: return {face.member, face.column, face.row};
      default: return {face.member, face.row, face.column};
    }
  }

  /// May faces f and g (sides s of f, t of g, one hinge) be joined in one piece?
  bool joinable(const Side& s, const Side& t) const {
    const Face &f = mesh_.faces[s.face], &g = mesh_.faces[t.face];
    if (s.face == t.face || !is_valid_panel(f.shape) || !is_valid_panel(g.shape)) return false;
    // Opposite traversal: the faces agree on which side is the front.
    if (f.corners[s.edge] != g.corners[(t.edge + 1) % g.corners.size()]) return false;
    switch (options_.mode) {
      case PieceMode::strips: return f.row == g.row;  // a row of an array crosses its members
      case PieceMode::columns: return f.member == g.member && f.column == g.column;
      // A cell: its strips, hung from a spine of the first column (a comb, as papercraft unfolders lay out tubes).
      case PieceMode::cells: return f.member == g.member && (f.row == g.row || (f.column == 0 && g.column == 0));
      case PieceMode::panels: return false;
    }
    return false;
  }

  /// The faces joinable to f, best first: along the piece's line forwards, backwards, then across.
  /// Where three or four panels meet on a hinge (walls of an array), any two may be joined.
  std::vector<std::pair<Side, Side>> neighbours(std::size_t f) const {
    std::vector<std::pair<Side, Side>> out;
    const Face& face = mesh_.faces[f];
    for (std::size_t k = 0; k < face.corners.size(); ++k) {
      const Side s{f, k};
      for (const Side& t : mesh_.edges.at(mesh_.key(face, k, cells_))) {
        if (joinable(s, t)) out.push_back({s, t});
      }
    }
    auto rank = [&](const Side& t) {
      const Face& g = mesh_.faces[t.face];
      const bool along_rows = options_.mode != PieceMode::columns;
      const bool same_line = along_rows ? g.row == face.row : g.column == face.column;
      const std::size_t here = along_rows ? face.column : face.row, there = along_rows ? g.column : g.row;
      const bool forward = g.member != face.member || there == here + 1 || (there == 0 && here > 1);
      return (same_line ? 0 : 2) + (forward ? 0 : 1);
    };
    std::stable_sort(out.begin(), out.end(), [&](const auto& p, const auto& q) { return rank(p.second) < rank(q.second); });
    return out;
  }

  /// How much the scale must shrink for this shape to fit (1 when it fits).
  double shrink_to_fit(const Polygon2& shape) const {
    const Box2 box = minimum_box(shape);
    const double big = std::max(box.width, box.height), small = std::min(box.width, box.height);
    return std::min({1.0, std::max(fit_.x(), fit_.y()) / big, std::min(fit_.x(), fit_.y()) / std::max(small, 1e-300)});
  }

  /// Refuses a scale at which some panel is larger than the page's room, naming the largest.
  void check_single(const Polygon2& shape) const {
    if (fits(shape, fit_)) return;
    double least = 1.0;
    std::size_t worst = 0;
    for (std::size_t f = 0; f < mesh_.faces.size(); ++f) {
      const double shrink = shrink_to_fit(flat(mesh_, mesh_.faces[f], scale_));
      if (shrink < least) least = shrink, worst = f;
    }
    const Box2 box = minimum_box(flat(mesh_, mesh_.faces[worst], scale_));
    throw InvalidInputError("--scale", "panel P" + std::to_string(mesh_.faces[worst].panel) + " is " + mm(box.width) +
                                           " x " + mm(box.height) + " mm at " + format_number(scale_) +
                                           " mm per model unit, larger than the page's room for pieces (" +
                                           mm(fit_.x()) + " x " + mm(fit_.y()) + " mm); use --scale " +
                                           format_number(std::floor(scale_ * least * 0.999 * 1000.0) / 1000.0) +
                                           " or less, or a larger --page");
  }

  void grow(std::size_t seed) {
    Piece piece;
    const std::size_t id = pieces_.size();
    auto add = [&](std::size_t f, Polygon2 outline) {
      const Face& face = mesh_.faces[f];
      piece_of_[f] = id;
      slot_[f] = piece.panels.size();
      placed_[f] = outline;
      piece.panels.push_back(PiecePanel{face.panel, face.member, face.row, face.column, std::move(outline),
                                        face.corners, face.shape});
    };
    const Polygon2 first = flat(mesh_, mesh_.faces[seed], scale_);
    check_single(first);
    add(seed, first);
    piece.cuttable = is_valid_panel(mesh_.faces[seed].shape);
    std::vector<Vec2> points(first.begin(), first.end());
    std::vector<std::size_t> stack{seed};
    while (!stack.empty()) {
      const std::size_t f = stack.back();
      stack.pop_back();
      const auto next = neighbours(f);
      std::vector<std::size_t> placed_now;  // best first; explored best first too (pushed last)
      for (const auto& [s, t] : next) {
        if (piece_of_[t.face] != none || joined_.count({s.face, s.edge})) continue;
        // g's corners t.edge + 1 and t.edge are f's corners s.edge and s.edge + 1.
        const Face& g = mesh_.faces[t.face];
        const std::size_t n = g.corners.size(), m = mesh_.faces[f].corners.size();
        // A fold shorter than this tears or cannot be creased: glue there instead.
        if ((placed_[f][(s.edge + 1) % m] - placed_[f][s.edge]).norm() < shortest_fold_mm) continue;
        const Polygon2 shape = attach(flat(mesh_, g, scale_), (t.edge + 1) % n, t.edge, placed_[f][s.edge],
                                      placed_[f][(s.edge + 1) % m]);
        if (!room_for(piece, shape, points)) continue;
        points.insert(points.end(), shape.begin(), shape.end());
        add(t.face, shape);
        tree_.push_back({s, t});
        joined_.insert({s.face, s.edge});
        joined_.insert({t.face, t.edge});
        placed_now.push_back(t.face);
      }
      stack.insert(stack.end(), placed_now.rbegin(), placed_now.rend());
    }
    pieces_.push_back(std::move(piece));
  }

  bool room_for(const Piece& piece, const Polygon2& shape, std::vector<Vec2> points) const {
    for (const PiecePanel& p : piece.panels) {
      if (polygon_overlap(p.outline, shape) > contact_mm) return false;
    }
    points.insert(points.end(), shape.begin(), shape.end());
    return fits(points, fit_);
  }

  bool same_segment(const Side& s, const Side& t) const {
    const auto& p = placed_[s.face];
    const auto& q = placed_[t.face];
    const std::size_t n = p.size(), m = q.size();
    return (p[s.edge] - q[(t.edge + 1) % m]).norm() <= contact_mm && (p[(s.edge + 1) % n] - q[t.edge]).norm() <= contact_mm;
  }

  void add_fold(const Side& s, const Side& t) {
    Piece& piece = pieces_[piece_of_[s.face]];
    const Face &f = mesh_.faces[s.face], &g = mesh_.faces[t.face];
    const Vec3 a = mesh_.x[f.corners[s.edge]], b = mesh_.x[f.corners[(s.edge + 1) % f.corners.size()]];
    PieceFold fold{slot_[s.face], slot_[t.face], placed_[s.face][s.edge],
                   placed_[s.face][(s.edge + 1) % f.corners.size()], fold_angle_degrees(f.normal, g.normal, a, b)};
    fold.style = std::abs(fold.angle_degrees) < 1e-6 ? LineStyle::flat
                 : fold.angle_degrees > 0.0      ? LineStyle::valley
                                                 : LineStyle::mountain;
    piece.folds.push_back(fold);
    folded_.insert({s.face, s.edge});
    folded_.insert({t.face, t.edge});
  }

  void find_folds_and_seams(std::size_t& seams) {
    for (const auto& [s, t] : tree_) add_fold(s, t);
    // A hinge whose two sides landed on the same line of one piece is a fold too.
    for (const auto& [key, sides] : mesh_.edges) {
      if (sides.size() != 2 || folded_.count({sides[0].face, sides[0].edge})) continue;
      if (piece_of_[sides[0].face] == piece_of_[sides[1].face] && joinable(sides[0], sides[1]) &&
          same_segment(sides[0], sides[1])) {
        add_fold(sides[0], sides[1]);
      }
    }
    // Seams, numbered in the order pieces and their panels' edges are met.
    std::map<std::tuple<std::size_t, std::size_t, std::size_t>, std::size_t> seam_of;
    std::vector<std::vector<std::pair<std::size_t, std::size_t>>> sides_of;  // seam -> (piece, index in piece.seams)
    for (std::size_t p = 0; p < pieces_.size(); ++p) {
      Piece& piece = pieces_[p];
      for (std::size_t i = 0; i < piece.panels.size(); ++i) {
        const Face& face = mesh_.faces[face_of(piece.panels[i], p)];
        for (std::size_t k = 0; k < face.corners.size(); ++k) {
          const auto key = mesh_.key(face, k, cells_);
          const auto& sides = mesh_.edges.at(key);
          const std::size_t f = face_of(piece.panels[i], p);
          std::size_t loose = 0, on_sheets = 0;  // sides of this hinge that are not fold lines; that are on the sheets
          for (const Side& t : sides) {
            loose += folded_.count({t.face, t.edge}) ? 0 : 1;
            on_sheets += off_the_sheets(t.face) ? 0 : 1;
          }
          if (on_sheets < 2 || loose == 0) continue;
          const bool on_fold = folded_.count({f, k}) > 0;
          // A fold line that is also a seam (a wall meets it) carries the label once, on its first panel.
          if (on_fold && labelled_folds_.count(key)) continue;
          if (on_fold) labelled_folds_.insert(key);
          auto [it, fresh] = seam_of.try_emplace(key, seam_of.size() + 1);
          if (fresh) sides_of.emplace_back();
          sides_of[it->second - 1].push_back({p, piece.seams.size()});
          piece.seams.push_back(SeamSide{it->second, i, k, std::nullopt, on_fold});
        }
      }
    }
    seams = seam_of.size();
    if (!options_.tabs) return;
    // The tab goes on the side that leaves the seam's smallest label largest: a
    // tab carries its side's label, the other sides carry theirs inside their panel.
    for (const auto& sides : sides_of) {
      auto label = [](const Polygon2& region, std::size_t edge, const SeamSide& side) {
        const auto box = fit_label(region, edge, "S" + std::to_string(side.seam), 3.0, {});
        return box ? box->height : 0.0;
      };
      std::vector<double> room;
      for (const auto& [p, s] : sides) {
        const SeamSide& side = pieces_[p].seams[s];
        room.push_back(side.on_fold ? 3.0 : label(pieces_[p].panels[side.panel].outline, side.edge, side));
      }
      std::optional<std::size_t> best;
      SeamSide best_side;
      double best_score = -1.0;
      bool any_cuttable = false;
      for (const auto& [p, s] : sides) any_cuttable = any_cuttable || pieces_[p].cuttable;
      for (std::size_t k = 0; k < sides.size(); ++k) {
        const auto& [p, s] = sides[k];
        if (any_cuttable && !pieces_[p].cuttable) continue;  // no tab on a panel that cannot be cut
        SeamSide trial = pieces_[p].seams[s];
        if (!add_tab(pieces_[p], trial)) continue;
        const Polygon2& t = *trial.tab;
        double score = std::max(room[k], label(Polygon2{t[1], t[0], t[3], t[2]}, 0, trial));
        for (std::size_t j = 0; j < sides.size(); ++j) score = j == k ? score : std::min(score, room[j]);
        if (score > best_score + 1e-9) best = k, best_side = trial, best_score = score;
      }
      if (best) pieces_[sides[*best].first].seams[sides[*best].second] = best_side;
    }
  }

  /// The mesh face of a piece's panel (piece p holds it).
  std::size_t face_of(const PiecePanel& panel, std::size_t p) const {
    // Faces are found through their slot; build the reverse map lazily.
    if (face_at_.empty()) {
      face_at_.resize(pieces_.size());
      for (std::size_t f = 0; f < mesh_.faces.size(); ++f) {
        if (piece_of_[f] == none) continue;  // left off the sheets
        auto& list = face_at_[piece_of_[f]];
        if (list.size() <= slot_[f]) list.resize(slot_[f] + 1);
        list[slot_[f]] = f;
      }
    }
    return face_at_[p][&panel - pieces_[p].panels.data()];
  }

  /// A tab on this side if it clears the piece's panels and tabs (full depth, then half).
  bool add_tab(Piece& piece, SeamSide& side) const {
    if (side.on_fold) return false;
    const Polygon2& outline = piece.panels[side.panel].outline;
    const Vec2 a = outline[side.edge], b = outline[(side.edge + 1) % outline.size()];
    const double length = (b - a).norm();
    if (length <= contact_mm) return false;
    const Vec2 along = (b - a) / length, out(along.y(), -along.x());  // counter-clockwise outline: outside on the right
    // Deep enough to hold and to carry its label (4 mm), however short the seam.
    for (double depth = std::min(std::max(options_.tab_depth * length, 4.0), options_.max_tab_mm); depth >= 0.5;
         depth *= 0.5) {
      const double inset = std::min(depth, 0.3 * length);
      Polygon2 tab{a, b, b + depth * out - inset * along, a + depth * out + inset * along};
      bool clear = true;
      for (const PiecePanel& p : piece.panels) clear = clear && polygon_overlap(p.outline, tab) <= contact_mm;
      for (const SeamSide& s : piece.seams) clear = clear && (!s.tab || polygon_overlap(*s.tab, tab) <= contact_mm);
      if (clear) {
        side.tab = std::move(tab);
        return true;
      }
    }
    return false;
  }

  Mesh mesh_;
  const CutSheetOptions& options_;
  double scale_;
  Vec2 fit_;
  bool cells_;
  std::vector<std::size_t> piece_of_, slot_;
  std::vector<Polygon2> placed_;
  std::vector<std::pair<Side, Side>> tree_;
  std::set<std::pair<std::size_t, std::size_t>> folded_, joined_;
  std::set<std::tuple<std::size_t, std::size_t, std::size_t>> labelled_folds_;
  mutable std::vector<std::vector<std::size_t>> face_at_;
  std::vector<Piece> pieces_;
};

}  // namespace

std::vector<Piece> unfold_pieces(const Design& design, const CutSheetOptions& options, double scale, Vec2 fit,
                                 std::size_t& seams, std::vector<std::size_t>& left_out) {
  std::vector<Piece> pieces = Unfolder(design, options, scale, fit).run(seams, left_out);
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    pieces[k].number = k + 1;
    place_labels(pieces[k]);
  }
  return pieces;
}

}  // namespace phedra::sheets
