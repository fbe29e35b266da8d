// Labels that fit (issue 17, item 2): every label is a box inside its panel,
// as large as fits up to a readable maximum, clear of the panel's other labels.

#include "cut_sheet_parts.h"

#include <algorithm>
#include <cstdint>
#include <unordered_map>
#include <cctype>
#include <cmath>

namespace phedra::sheets {
namespace {

constexpr double panel_label_mm = 3.5;  ///< capital height at most
constexpr double seam_label_mm = 3.0;
constexpr double smallest_mm = 0.1;
/// A label of capital height h keeps 0.15 h inside its panel (or tab), and one
/// of at least 1.6 mm keeps min(0.25 h, this): half a fold line's width (0.3 mm)
/// and room for the glyphs' overshoot, so that no fold line runs through it as
/// printed (issue 27: P161, P143 on grid-3x3's sheet 3 sat 0.29 mm from their
/// hinges, the dashes through their baselines). Smaller labels on slim panels
/// keep 0.15 h, so as not to fall below the readable 1.2 mm (a label beside the
/// piece with a leader is the way for them: not done yet).
constexpr double clearance_mm = 0.45;

double clearance(double h) { return h >= 1.6 ? std::max(0.15 * h, std::min(0.25 * h, clearance_mm)) : 0.15 * h; }

bool clear_of(const Box2& box, const std::vector<Box2>& avoid, double gap) {
  // Boxes whose circumscribed circles are more than the gap apart are clear: most
  // of them, on a piece of hundreds of labels (grid-10x10's sheets: 36 -> 12 s).
  auto centre = [](const Box2& b) -> Vec2 { return b.origin + 0.5 * b.width * b.axis + 0.5 * b.height * b.up(); };
  auto radius = [](const Box2& b) { return 0.5 * std::sqrt(b.width * b.width + b.height * b.height); };
  const Vec2 c = centre(box);
  const double r = radius(box);
  const Polygon2 corners = box.corners();
  for (const Box2& other : avoid) {
    const double reach = r + radius(other) + gap;
    if ((centre(other) - c).squaredNorm() > reach * reach) continue;
    if (convex_overlap(corners, other.corners()) > -gap) return false;
  }
  return true;
}

/// The area centroid and the direction of the longest edge.
std::pair<Vec2, Vec2> centre_and_axis(const Polygon2& outline) {
  Vec2 centre = Vec2::Zero();
  double area = 0.0;
  std::size_t longest = 0;
  const std::size_t n = outline.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 &p = outline[k], &q = outline[(k + 1) % n];
    const double c = p.x() * q.y() - p.y() * q.x();
    area += c;
    centre += c * (p + q);
    if ((q - p).squaredNorm() > (outline[(longest + 1) % n] - outline[longest]).squaredNorm()) longest = k;
  }
  centre = std::abs(area) > 1e-12 ? Vec2(centre / (3.0 * area)) : outline.front();
  Vec2 axis = outline[(longest + 1) % n] - outline[longest];
  axis = axis.squaredNorm() > 0.0 ? Vec2(axis.normalized()) : Vec2::UnitX();
  return {centre, axis};
}

/// The label box of capital height h: centred on `centre` along `axis`, or along
/// edge `edge`, centred on `centre` (a point of the edge).
Box2 label_box(const Polygon2& outline, std::optional<std::size_t> edge, double width_per_height, double h,
               const Vec2& centre, const Vec2& centre_axis) {
  const double w = width_per_height * h;
  if (!edge) {
    const Vec2 up(-centre_axis.y(), centre_axis.x());
    return Box2{centre - 0.5 * w * centre_axis - 0.5 * h * up, centre_axis, w, h};
  }
  const Vec2 a = outline[*edge], b = outline[(*edge + 1) % outline.size()];
  Vec2 axis = b - a;
  axis = axis.squaredNorm() > 0.0 ? Vec2(axis.normalized()) : Vec2::UnitX();
  const Vec2 inward(-axis.y(), axis.x());  // counter-clockwise outline: inside on the left
  return Box2{centre - 0.5 * w * axis + 0.3 * h * inward, axis, w, h};
}

}  // namespace

Box2 upright(const Box2& box) {
  // Left to right, or (steeper than 60 degrees, either side) bottom to top, as drawings label
  // steep lines: a label at 60-75 degrees read downward before (issue 27), which a reader
  // turns the sheet for. (Deciding the band by |x|: a near-vertical axis with a tiny
  // negative x was turned to read downward before that.)
  const bool near_vertical = std::abs(box.axis.x()) < 0.5;
  const bool upside_down = near_vertical ? box.axis.y() < 0.0 : box.axis.x() < 0.0;
  if (!upside_down) return box;
  return Box2{box.origin + box.width * box.axis + box.height * box.up(), -box.axis, box.width, box.height};
}

std::optional<Box2> fit_label(const Polygon2& outline, std::optional<std::size_t> edge, const std::string& text,
                              double max_height, const std::vector<Box2>& avoid) {
  const double ratio = text_width(text, 1.0);
  // (Not a structured binding: the lambdas below capture these, which clang refuses before C++20's P1091 lands.)
  const std::pair<Vec2, Vec2> frame = centre_and_axis(outline);
  const Vec2 centroid = frame.first;
  Vec2 axis = frame.second;  // a panel label tries every edge's direction (below)
  auto fits = [&](const Vec2& centre, double h) {
    const Box2 box = label_box(outline, edge, ratio, h, centre, axis);
    return box_inside(outline, box, clearance(h)) && clear_of(box, avoid, 0.15 * h);
  };
  // The largest height that fits at one centre (bisection), 0 when nothing does.
  auto largest = [&](const Vec2& centre) {
    auto ok = [&](double h) { return fits(centre, h); };
    if (ok(max_height)) return max_height;
    double lo = 0.0, hi = max_height;
    for (int i = 0; i < 14; ++i) {  // to max_height / 16384: finer than print
      const double mid = 0.5 * (lo + hi);
      (ok(mid) ? lo : hi) = mid;
    }
    return lo >= smallest_mm && ok(lo) ? lo : 0.0;
  };
  if (edge) {
    // Along the seam: its middle first, then towards either end (a slim panel is wider at one).
    const Vec2 a = outline[*edge], b = outline[(*edge + 1) % outline.size()];
    Vec2 best_centre = 0.5 * (a + b);
    double best = largest(best_centre);
    if (best < 0.7 * max_height) {
      // (Only when squeezed: a label off the middle takes room the panel's own label may need.)
      for (double f : {0.35, 0.65, 0.2, 0.8}) {
        const Vec2 c = a + f * (b - a);
        if (!fits(c, 1.15 * best)) continue;  // cannot beat the middle
        const double h = largest(c);
        if (h > 1.15 * best) best = h, best_centre = c;
      }
    }
    if (best <= 0.0) return std::nullopt;
    return label_box(outline, edge, ratio, best, best_centre, axis);
  }
  // A panel label: along the longest edge first, then along the others; at the
  // centroid, then (when squeezed) at a grid of centres.
  std::vector<Vec2> axes{frame.second};
  for (std::size_t k = 0; k < outline.size(); ++k) {
    const Vec2 e = outline[(k + 1) % outline.size()] - outline[k];
    if (e.squaredNorm() == 0.0) continue;
    const Vec2 d = e.normalized();
    bool known = false;
    for (const Vec2& other : axes) known = known || std::abs(std::abs(d.dot(other)) - 1.0) < 1e-3;
    if (!known) axes.push_back(d);
  }
  Vec2 best_centre = centroid, best_axis = frame.second;
  double best = 0.0;
  for (const Vec2& candidate : axes) {
    axis = candidate;
    if (best > 0.0 && !fits(centroid, std::min(1.1 * best, max_height)) && best >= 0.5 * max_height) continue;
    double here = largest(centroid);
    Vec2 here_centre = centroid;
    if (here < max_height) {
      // Squeezed at the centroid (by seam labels, or a slim panel): a grid of centres.
      const Vec2 up(-axis.y(), axis.x());
      double s0 = 1e300, s1 = -1e300, t0 = 1e300, t1 = -1e300;
      for (const Vec2& p : outline) {
        s0 = std::min(s0, (p - centroid).dot(axis)), s1 = std::max(s1, (p - centroid).dot(axis));
        t0 = std::min(t0, (p - centroid).dot(up)), t1 = std::max(t1, (p - centroid).dot(up));
      }
      const double target = std::max(here, best);
      for (int i = 1; i < 6; ++i) {
        for (int j = 1; j < 6; ++j) {
          const Vec2 c = centroid + (s0 + (s1 - s0) * i / 6.0) * axis + (t0 + (t1 - t0) * j / 6.0) * up;
          if (!inside(outline, c) || !fits(c, std::min(1.05 * std::max(target, here), max_height))) continue;
          const double h = largest(c);
          if (h > 1.05 * here) here = h, here_centre = c;
        }
      }
    }
    if (here > 1.1 * best) best = here, best_centre = here_centre, best_axis = axis;  // the first axis wins ties
    if (best >= max_height) break;
  }
  if (best <= 0.0) return std::nullopt;
  return label_box(outline, edge, ratio, best, best_centre, best_axis);
}

namespace {

/// The seam labels of panel i with every label at most `cap` high: on the
/// side's tab when it has one (`on_tab`, found once), else along the seam
/// inside the panel.
std::vector<SheetText> seam_labels(const Piece& piece, std::size_t i, double cap,
                                   const std::vector<std::optional<Box2>>& on_tab, double& smallest) {
  std::vector<SheetText> out;
  std::vector<Box2> taken;
  smallest = cap;
  for (std::size_t k = 0; k < piece.seams.size(); ++k) {
    const SeamSide& side = piece.seams[k];
    if (side.panel != i) continue;
    const std::string text = "S" + std::to_string(side.seam);
    std::optional<Box2> box = on_tab[k];
    // A tab carries its seam's label whenever it is readable there (a maker looks for it on the tab).
    if (!box || (box->height < readable_label_mm && box->height < 0.8 * cap)) {
      auto on_panel = fit_label(piece.panels[i].outline, side.edge, text, cap, taken);
      if (on_panel && (!box || on_panel->height > box->height)) {
        taken.push_back(*on_panel);
        box = on_panel;
      }
    }
    smallest = std::min(smallest, box ? box->height : 0.0);
    out.push_back(SheetText{text, box ? *box : no_room(seam_anchor(piece.panels[i].outline, side.edge)), TextRole::seam});
  }
  return out;
}

}  // namespace

void place_labels(Piece& piece) {
  std::vector<std::optional<Box2>> on_tab(piece.seams.size());
  for (std::size_t k = 0; k < piece.seams.size(); ++k) {
    if (const auto& t = piece.seams[k].tab) {
      // Along the seam on the tab (its corners are a, b, then outside: turned counter-clockwise).
      on_tab[k] = fit_label(Polygon2{(*t)[1], (*t)[0], (*t)[3], (*t)[2]}, 0, "S" + std::to_string(piece.seams[k].seam),
                            seam_label_mm, {});
    }
  }
  for (std::size_t i = 0; i < piece.panels.size(); ++i) {
    const PiecePanel& panel = piece.panels[i];
    // The piece's number (its place in the assembly order) on its first panel, as on plates.
    const std::string name = (i == 0 && piece.number > 0 ? std::to_string(piece.number) + " " : std::string()) + "P" +
                             std::to_string(panel.panel);
    // A panel that is not a simple polygon (red, not to be cut) is named inside its convex hull.
    const Polygon2 region = piece.cuttable ? panel.outline : convex_hull(panel.outline);
    // The labels sharing a slim panel: one cap for its seam labels, the one
    // that keeps most of its labels (its name too) readable inside, then makes
    // the smallest largest; the first label placed would otherwise take the
    // room of the others. The rest are called out beside the piece.
    std::pair<std::size_t, double> best_score{0, -1.0};
    std::vector<SheetText> best;
    for (double cap : {seam_label_mm, 2.4, readable_label_mm}) {
      double smallest = 0.0;
      std::vector<SheetText> labels = seam_labels(piece, i, cap, on_tab, smallest);
      std::vector<Box2> taken;
      for (const SheetText& label : labels) {
        if (label.box.height > 0.0) taken.push_back(label.box);
      }
      const auto box = fit_label(region, std::nullopt, name, panel_label_mm, taken);
      labels.push_back(SheetText{name, box ? *box : no_room(panel_anchor(region)), TextRole::panel});
      smallest = std::min(smallest, box ? box->height : 0.0);
      const std::pair<std::size_t, double> score{readable_inside(labels), smallest};
      if (best.empty() || score.first > best_score.first || (score.first == best_score.first && score.second > best_score.second + 1e-9)) {
        best_score = score, best = std::move(labels);
      }
      if (smallest >= cap - 1e-9) break;  // every label at least the cap: a lower cap cannot do better
    }
    for (SheetText& label : best) piece.labels.push_back(std::move(label));
  }
  call_out_small_labels(piece);
}

Vec2 panel_anchor(const Polygon2& region) {
  const Vec2 centre = centre_and_axis(region).first;
  if (inside(region, centre)) return centre;
  Vec2 mean = Vec2::Zero();
  for (const Vec2& p : region) mean += p;
  return mean / static_cast<double>(std::max<std::size_t>(region.size(), 1));
}

Vec2 seam_anchor(const Polygon2& outline, std::size_t edge) {
  const Vec2 a = outline[edge], b = outline[(edge + 1) % outline.size()];
  const Vec2 middle = 0.5 * (a + b);
  if ((b - a).squaredNorm() == 0.0) return middle;
  const Vec2 inward = Vec2(a.y() - b.y(), b.x() - a.x()).normalized();  // counter-clockwise: inside on the left
  for (double step : {0.3, 0.1, 0.03}) {
    if (inside(outline, middle + step * inward)) return middle + step * inward;
  }
  return middle;
}


}  // namespace phedra::sheets

namespace phedra::sheets {

Box2 no_room(const Vec2& anchor) { return Box2{anchor, Vec2::UnitX(), 0.0, 0.0}; }

std::size_t readable_inside(const std::vector<SheetText>& labels) {
  return static_cast<std::size_t>(std::count_if(labels.begin(), labels.end(), [](const SheetText& t) { return t.box.height >= readable_label_mm; }));
}

namespace {

/// Whether segment a-b passes within `gap` of the box (Liang-Barsky in the box's frame).
bool segment_meets_box(const Vec2& a, const Vec2& b, const Box2& box, double gap) {
  const Vec2 pa(( a - box.origin).dot(box.axis), (a - box.origin).dot(box.up()));
  const Vec2 pb((b - box.origin).dot(box.axis), (b - box.origin).dot(box.up()));
  const Vec2 d = pb - pa, lo(-gap, -gap), hi(box.width + gap, box.height + gap);
  double t0 = 0.0, t1 = 1.0;
  for (int i = 0; i < 2; ++i) {
    if (std::abs(d[i]) < 1e-15) {
      if (pa[i] < lo[i] || pa[i] > hi[i]) return false;
      continue;
    }
    double u0 = (lo[i] - pa[i]) / d[i], u1 = (hi[i] - pa[i]) / d[i];
    if (u0 > u1) std::swap(u0, u1);
    t0 = std::max(t0, u0), t1 = std::min(t1, u1);
    if (t0 > t1) return false;
  }
  return true;
}

/// Labels on a grid of square cells (by their circumscribed circles), so that a
/// candidate is tested against the labels near it, not all of a piece's hundreds.
class LabelIndex {
 public:
  void add(const Box2& box) {
    boxes_.push_back(box);
    for_cells(box, 0.0, [&](std::int64_t key) { cells_[key].push_back(boxes_.size() - 1); });
  }
  /// Whether `box` keeps `gap` from every label added (clear_of's test).
  bool clear(const Box2& box, double gap) const {
    ++stamp_;
    seen_.resize(boxes_.size(), 0);
    const Polygon2 corners = box.corners();
    bool clear = true;
    for_cells(box, gap, [&](std::int64_t key) {
      const auto found = cells_.find(key);
      if (!clear || found == cells_.end()) return;
      for (std::size_t k : found->second) {
        if (seen_[k] == stamp_) continue;
        seen_[k] = stamp_;
        if (convex_overlap(corners, boxes_[k].corners()) > -gap) {
          clear = false;
          return;
        }
      }
    });
    return clear;
  }
  const std::vector<Box2>& boxes() const { return boxes_; }

 private:
  static constexpr double cell = 4.0;  // mm
  template <class F>
  static void for_cells(const Box2& box, double margin, F&& f) {
    const Vec2 c = box.origin + 0.5 * box.width * box.axis + 0.5 * box.height * box.up();
    const double r = 0.5 * std::sqrt(box.width * box.width + box.height * box.height) + margin;
    const auto lo = ((c.array() - r) / cell).floor().cast<std::int64_t>();
    const auto hi = ((c.array() + r) / cell).floor().cast<std::int64_t>();
    for (std::int64_t x = lo.x(); x <= hi.x(); ++x) {
      for (std::int64_t y = lo.y(); y <= hi.y(); ++y) f((x << 32) ^ (y & 0xffffffff));
    }
  }
  std::vector<Box2> boxes_;
  std::unordered_map<std::int64_t, std::vector<std::size_t>> cells_;
  mutable std::vector<std::uint64_t> seen_;  // the query that last tested each label
  mutable std::uint64_t stamp_ = 0;
};

}  // namespace

void call_out_small_labels(Piece& piece) {
  std::vector<std::size_t> small;
  LabelIndex kept;
  for (std::size_t k = 0; k < piece.labels.size(); ++k) {
    if (piece.labels[k].box.height < readable_label_mm) {
      small.push_back(k);
    } else {
      kept.add(piece.labels[k].box);
    }
  }
  if (small.empty()) return;
  // What a called-out label keeps clear of: the piece's panels (their hulls when
  // it cannot be cut), tabs and cut outline, by a gap; its other labels.
  std::vector<Polygon2> shapes;
  for (const PiecePanel& p : piece.panels) shapes.push_back(piece.cuttable ? p.outline : convex_hull(p.outline));
  for (const SeamSide& s : piece.seams) {
    if (s.tab) shapes.push_back(*s.tab);
  }
  if (piece.cut) shapes.push_back(*piece.cut);
  std::vector<std::pair<Vec2, Vec2>> bounds;
  std::vector<std::vector<Polygon2>> parts;  // each shape's convex parts (polygon_overlap's, once)
  for (const Polygon2& shape : shapes) {
    Vec2 lo = shape.front(), hi = shape.front();
    for (const Vec2& p : shape) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    bounds.push_back({lo, hi});
    parts.push_back(convex_parts(shape));
  }
  constexpr double shape_gap = 0.5, label_gap = 0.4;
  std::vector<std::pair<Vec2, Vec2>> leaders;
  auto free = [&](const Box2& box) {
    const Polygon2 corners = box.corners();
    const Vec2 lo = box.origin - Vec2::Constant(shape_gap), hi = box.origin + Vec2(box.width, box.height) + Vec2::Constant(shape_gap);
    for (std::size_t k = 0; k < shapes.size(); ++k) {
      if ((bounds[k].first.array() > hi.array()).any() || (lo.array() > bounds[k].second.array()).any()) continue;
      for (const Polygon2& part : parts[k]) {
        if (convex_overlap(corners, part) > -shape_gap) return false;
      }
    }
    if (!kept.clear(box, label_gap)) return false;
    for (const auto& [a, b] : leaders) {  // (nor on an earlier label's leader)
      if (segment_meets_box(a, b, box, label_gap)) return false;
    }
    return true;
  };
  // A leader runs through no other label (the last 0.2 mm of it, at its own label, aside).
  auto leader_clear = [&](const Vec2& anchor, const Box2& box) {
    const Vec2 end = nearest_point(box, anchor);
    const double length = (end - anchor).norm();
    if (length < 0.3) return true;
    const Vec2 stop = end - 0.2 * (end - anchor) / length;
    for (const Box2& other : kept.boxes()) {
      if (segment_meets_box(anchor, stop, other, 0.1)) return false;
    }
    return true;
  };
  // Directions: across the piece's long side first (a strip's labels go above or below it).
  std::vector<Vec2> directions;
  for (double degrees : {90.0, 270.0, 0.0, 180.0, 60.0, 120.0, 240.0, 300.0, 30.0, 150.0, 210.0, 330.0}) {
    const double a = degrees * M_PI / 180.0;
    directions.emplace_back(std::cos(a), std::sin(a));
  }
  for (const std::size_t k : small) {
    SheetText& label = piece.labels[k];
    const Box2& was = label.box;
    const Vec2 anchor = was.height > 0.0 ? Vec2(was.origin + 0.5 * was.width * was.axis + 0.5 * was.height * was.up()) : was.origin;
    const double h = readable_label_mm, w = text_width(label.text, h);
    // Within 25 mm with a leader through no other label; else the nearest free place.
    std::optional<Box2> found;
    for (const bool strict : {true, false}) {
      for (double d = 0.5; !found && d < (strict ? 25.0 : 400.0); d += d < 10.0 ? 0.5 : 2.0) {
        for (const Vec2& dir : directions) {
          const double reach = 0.5 * (w * std::abs(dir.x()) + h * std::abs(dir.y()));
          const Vec2 centre = anchor + (d + reach) * dir;
          const Box2 box{centre - Vec2(0.5 * w, 0.5 * h), Vec2::UnitX(), w, h};
          if (free(box) && (!strict || leader_clear(anchor, box))) {
            found = box;
            break;
          }
        }
      }
      if (found) break;
    }
    if (!found) continue;  // (beyond 400 mm of everything: cannot happen on a piece that fits a page)
    label.box = *found;
    label.leader = anchor;
    kept.add(*found);
    leaders.push_back({anchor, nearest_point(*found, anchor)});
  }
}

}  // namespace phedra::sheets
