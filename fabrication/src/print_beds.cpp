// Parts laid flat for printing (print_beds.h).

#include "phedra/print_beds.h"

#include "cut_sheet_parts.h"
#include "phedra/errors.h"
#include "phedra/number_format.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <tuple>

namespace phedra {
namespace {

/// A flat face of a solid: its triangles that share one plane (unit outward
/// normal n, n . x = offset), their total area.
struct FlatFace {
  Vec3 normal;
  double offset = 0.0, area = 0.0;
};

/// The solid's flat faces, the largest first.
std::vector<FlatFace> flat_faces(const Solid& solid, double size) {
  std::vector<FlatFace> faces;
  for (const auto& t : solid.triangles) {
    const Vec3 &a = solid.vertices[t[0]], &b = solid.vertices[t[1]], &c = solid.vertices[t[2]];
    const Vec3 cross = (b - a).cross(c - a);
    const double twice = cross.norm();
    if (!(twice > 0.0)) continue;
    const Vec3 n = cross / twice;
    const double offset = n.dot(a);
    auto same = std::find_if(faces.begin(), faces.end(), [&](const FlatFace& f) {
      return f.normal.dot(n) > 1.0 - 1e-9 && std::abs(f.offset - offset) <= 1e-9 * size;
    });
    if (same == faces.end()) {
      faces.push_back(FlatFace{n, offset, 0.5 * twice});
    } else {
      same->area += 0.5 * twice;
    }
  }
  std::stable_sort(faces.begin(), faces.end(), [](const FlatFace& f, const FlatFace& g) { return f.area > g.area; });
  return faces;
}

/// The area of the solid's faces that would need support standing on `base`:
/// those facing down more steeply than 45 degrees (outward normal within 45
/// degrees of the base's), the base aside.
double overhang(const Solid& solid, const FlatFace& base, double flat) {
  double area = 0.0;
  for (const auto& t : solid.triangles) {
    const Vec3 &a = solid.vertices[t[0]], &b = solid.vertices[t[1]], &c = solid.vertices[t[2]];
    const Vec3 cross = (b - a).cross(c - a);
    const double twice = cross.norm();
    if (!(twice > 0.0)) continue;
    const bool on_base = std::abs(base.normal.dot(a) - base.offset) <= flat && std::abs(base.normal.dot(b) - base.offset) <= flat &&
                         std::abs(base.normal.dot(c) - base.offset) <= flat;
    if (!on_base && base.normal.dot(cross) > std::sqrt(0.5) * twice) area += 0.5 * twice;
  }
  return area;
}

/// The solid on the flat face it prints best on: of the faces with the whole
/// part above them, the one that leaves the least overhang (none for a plate on
/// its bottom, a knuckle or a pin on its end), the largest of those; that face at
/// z = 0 (snapped there exactly), turned about z so that its footprint's
/// smallest box lies along x, the box's corner at the origin.
std::pair<Solid, double> laid_flat(const Solid& solid, const std::string& name) {
  Vec3 low = solid.vertices.front(), high = low;
  for (const Vec3& v : solid.vertices) low = low.cwiseMin(v), high = high.cwiseMax(v);
  const double size = std::max((high - low).norm(), std::numeric_limits<double>::min());
  const double flat = 1e-9 * size;
  std::optional<FlatFace> base;
  double least = std::numeric_limits<double>::infinity();
  for (const FlatFace& f : flat_faces(solid, size)) {  // the largest first: a tie keeps the larger
    const bool above = std::all_of(solid.vertices.begin(), solid.vertices.end(),
                                   [&](const Vec3& v) { return f.normal.dot(v) <= f.offset + flat; });
    if (!above) continue;
    const double o = overhang(solid, f, flat);
    if (o < least - 1e-9 * size * size) {
      base = f;
      least = o;
    }
  }
  if (!base) {
    throw Error(ExitCode::internal, "part " + name + " has no flat face to lie on (a closed solid has one)");
  }
  // The face's outward normal turned to -z: the part stands on it.
  const Eigen::Matrix3d turn = Eigen::Quaterniond::FromTwoVectors(base->normal, -Vec3::UnitZ()).toRotationMatrix();
  Solid out = solid;
  std::vector<Vec2> footprint;
  for (Vec3& v : out.vertices) {
    v = turn * v;
    footprint.push_back(v.head<2>());
  }
  const Box2 box = minimum_box(footprint);
  const Vec2 up = box.up();
  const double floor = -base->offset;  // the face's z after the turn
  for (Vec3& v : out.vertices) {
    const Vec2 p = v.head<2>() - box.origin;
    const double z = v.z() - floor;
    v = Vec3(p.dot(box.axis), p.dot(up), std::abs(z) <= flat ? 0.0 : z);
  }
  return {out, base->area};
}

/// The part's footprint on the bed (its vertices' convex hull, seen from above).
Polygon2 footprint(const Solid& solid) {
  std::vector<Vec2> points;
  for (const Vec3& v : solid.vertices) points.push_back(v.head<2>());
  return convex_hull(points);
}

/// Quarter turns of a footprint in [0, w] x [0, h] about the vertical, kept in the positive quadrant.
Vec2 quarter_turn(const Vec2& p, int quarters, const Vec2& size) {
  switch (quarters) {
    case 1: return Vec2(size.y() - p.y(), p.x());
    case 2: return Vec2(size.x() - p.x(), size.y() - p.y());
    case 3: return Vec2(p.y(), size.x() - p.x());
    default: return p;
  }
}

std::string mm(double x) { return format_number(std::round(x * 10.0) / 10.0); }

}  // namespace

std::vector<const PrintPart*> PrintLayout::on_bed(std::size_t k) const {
  std::vector<const PrintPart*> out;
  for (const PrintPart& part : parts) {
    if (part.bed == k) out.push_back(&part);
  }
  return out;
}

Vec2 bed_size_from_string(const std::string& text) {
  const std::size_t x = text.find('x');
  auto number = [&](const std::string& s) -> std::optional<double> {
    if (s.empty()) return std::nullopt;
    std::size_t used = 0;
    try {
      const double v = std::stod(s, &used);
      if (used != s.size() || !(v >= 10.0 && v <= 1e4)) return std::nullopt;
      return v;
    } catch (const std::exception&) {
      return std::nullopt;
    }
  };
  if (x != std::string::npos) {
    const auto w = number(text.substr(0, x)), h = number(text.substr(x + 1));
    if (w && h) return Vec2(*w, *h);
  }
  throw InvalidInputError("--bed", "expected WxH in millimetres, each from 10 to 10000 (e.g. 200x200 or 250x210), got \"" +
                                       text + "\"");
}

PrintLayout lay_flat(const std::vector<Solid>& solids, const std::vector<std::string>& names, Vec2 bed, double gap) {
  if (!(bed.x() >= 10.0 && bed.y() >= 10.0 && bed.allFinite())) {
    throw InvalidInputError("--bed", "a bed is at least 10 x 10 mm");
  }
  if (!(gap >= 0.0) || !std::isfinite(gap)) throw InvalidInputError("--bed", "the gap between parts must be >= 0 mm");
  PrintLayout layout;
  layout.bed = bed;
  layout.gap = gap;
  const Vec2 room = bed - Vec2::Constant(2.0 * gap);  // the parts' area: the gap kept from the edges too
  std::vector<Vec2> sizes;
  std::vector<Polygon2> prints;
  for (std::size_t k = 0; k < solids.size(); ++k) {
    auto [solid, area] = laid_flat(solids[k], names[k]);
    Vec2 size = Vec2::Zero();
    for (const Vec3& v : solid.vertices) size = size.cwiseMax(v.head<2>());
    const bool fits = (size.x() <= room.x() && size.y() <= room.y()) || (size.y() <= room.x() && size.x() <= room.y());
    if (!fits) {
      throw InvalidInputError("--bed", "part " + names[k] + " is " + mm(size.x()) + " x " + mm(size.y()) +
                                           " mm laid flat: it fits no " + mm(bed.x()) + " x " + mm(bed.y()) +
                                           " mm bed with " + mm(gap) + " mm around it (a bed of " +
                                           mm(size.x() + 2.0 * gap) + " x " + mm(size.y() + 2.0 * gap) +
                                           " mm, or a smaller --scale or --model-size)");
    }
    prints.push_back(footprint(solid));
    sizes.push_back(size);
    layout.parts.push_back(PrintPart{names[k], std::move(solid), area, 0});
  }
  // The cut sheets' nesting: 1 mm cells, a part takes those within half the gap
  // of its footprint; the tallest first, each on the first bed with room, at the
  // highest then leftmost free place in whichever quarter turn sits highest.
  constexpr double cell = 1.0;
  const double reach = 0.5 * gap;
  const int pad = static_cast<int>(std::ceil(reach / cell)) + 2;
  const int columns = static_cast<int>(std::floor(room.x() / cell + 1e-9));
  const int rows = static_cast<int>(std::floor(room.y() / cell + 1e-9));
  std::vector<std::size_t> order(solids.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::min(sizes[a].x(), sizes[a].y()) * std::max(sizes[a].x(), sizes[a].y()) >
           std::min(sizes[b].x(), sizes[b].y()) * std::max(sizes[b].x(), sizes[b].y());
  });
  std::vector<sheets::CellMask> taken;
  for (const std::size_t k : order) {
    std::vector<int> turns;
    std::vector<sheets::CellMask> masks;
    std::vector<Vec2> turned_sizes;
    for (int q = 0; q < 4; ++q) {
      const Vec2 s = q % 2 ? Vec2(sizes[k].y(), sizes[k].x()) : sizes[k];
      if (s.x() > room.x() || s.y() > room.y()) continue;
      Polygon2 shape = prints[k];
      for (Vec2& p : shape) p = quarter_turn(p, q, sizes[k]);
      turns.push_back(q);
      turned_sizes.push_back(s);
      masks.push_back(sheets::CellMask::of_shapes({shape}, s, cell, reach, pad));
    }
    for (std::size_t b = 0;; ++b) {
      const bool fresh = b == taken.size();
      if (fresh) taken.emplace_back(columns + 2 * pad, rows + 2 * pad);
      std::optional<std::tuple<std::size_t, int, int>> best;
      for (std::size_t w = 0; w < masks.size(); ++w) {
        const int max_x = static_cast<int>(std::floor((room.x() - turned_sizes[w].x()) / cell + 1e-9));
        const int max_y = static_cast<int>(std::floor((room.y() - turned_sizes[w].y()) / cell + 1e-9));
        const auto found = taken[b].highest_fit(masks[w], max_x, max_y);
        if (found && (!best || found->second > std::get<2>(*best) ||
                      (found->second == std::get<2>(*best) && found->first < std::get<1>(*best)))) {
          best = std::tuple{w, found->first, found->second};
        }
      }
      if (!best) {
        if (fresh) throw Error(ExitCode::internal, "part " + names[k] + " fits no empty bed");
        continue;
      }
      const auto [w, x, y] = *best;
      taken[b].add(masks[w], x, y);
      PrintPart& part = layout.parts[k];
      part.bed = b;
      const Vec2 corner = Vec2::Constant(gap) + cell * Vec2(x, y);
      for (Vec3& v : part.solid.vertices) {
        const Vec2 p = quarter_turn(v.head<2>(), turns[w], sizes[k]) + corner;
        v.x() = p.x(), v.y() = p.y();
      }
      break;
    }
  }
  layout.beds = taken.size();
  return layout;
}

std::vector<std::size_t> plate_sheet_numbers(const Design& design) {
  CutSheetOptions options;
  options.mode = PieceMode::panels;  // as cut_sheets lays plates out: one piece a plate, in the same order
  options.tabs = false;
  std::size_t seams = 0;
  std::vector<std::size_t> left_out;
  const Vec2 any = Vec2::Constant(std::numeric_limits<double>::infinity());
  const std::vector<Piece> pieces = sheets::unfold_pieces(design, options, 1.0, any, seams, left_out);
  std::vector<std::size_t> numbers(panel_mesh(design).faces.size(), 0);
  for (const Piece& piece : pieces) {
    for (const PiecePanel& panel : piece.panels) numbers.at(panel.panel) = piece.number;
  }
  return numbers;
}

}  // namespace phedra
