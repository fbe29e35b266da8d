#include "phedra/crease_pattern.h"

#include "phedra/errors.h"
#include "phedra/number_format.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <sstream>

namespace phedra {
namespace {


/// A face's normal at the folded state, turned to agree with the viewer's side at the flat state.
Vec3 oriented_normal(const Quad& q, const Points& x, const std::vector<Vec2>& flat) {
  Vec3 n = Vec3::Zero();
  double area = 0.0;
  for (int k = 0; k < 4; ++k) {
    n += x[q[k]].cross(x[q[(k + 1) % 4]]);
    area += cross(flat[q[k]], flat[q[(k + 1) % 4]]);
  }
  return (area >= 0.0 ? 1.0 : -1.0) * n.normalized();
}

Vec2 centroid(const Quad& q, const std::vector<Vec2>& v) { return 0.25 * (v[q[0]] + v[q[1]] + v[q[2]] + v[q[3]]); }

}  // namespace

CreasePattern crease_pattern(const DevelopedPattern& pattern, const std::vector<int>& fold, double t_assignment,
                             double t) {
  const std::optional<Points> x = pattern.folded(t, fold), near = pattern.folded(t_assignment, fold);
  if (!x) throw InvalidInputError("--at", "the pattern cannot fold to t = " + format_number(t));
  if (!near) throw InvalidInputError("--at", "the pattern cannot fold to t = " + format_number(t_assignment));
  const GridTopology g = pattern.topology();
  CreasePattern c;
  c.name = pattern.input().name;
  c.t = t;
  c.t_assignment = t_assignment;
  c.apex_heights = pattern.input().apex_heights;
  for (const auto& row : pattern.flat()) {
    for (const Vec2& p : row) c.vertices.push_back(p);
  }
  c.faces = g.faces();
  std::map<std::pair<std::size_t, std::size_t>, std::vector<std::size_t>> faces_of;
  for (std::size_t f = 0; f < c.faces.size(); ++f) {
    for (int k = 0; k < 4; ++k) {
      const std::size_t a = c.faces[f][k], b = c.faces[f][(k + 1) % 4];
      faces_of[{std::min(a, b), std::max(a, b)}].push_back(f);
    }
  }
  const double flat_tolerance = 1e-12;  // radians
  for (const auto& entry : faces_of) {
    const std::pair<std::size_t, std::size_t> edge = entry.first;  // (captured below: no structured binding)
    const std::vector<std::size_t>& faces = entry.second;
    c.edges.push_back({edge.first, edge.second});
    if (faces.size() < 2) {
      c.assignment.push_back('B');
      c.fold_angle.push_back(0.0);
      continue;
    }
    // Face a lies to the left of the edge (u -> v) in the flat pattern.
    const Vec2 u = c.vertices[edge.first], v = c.vertices[edge.second];
    std::size_t a = faces[0], b = faces[1];
    if (cross(v - u, centroid(c.faces[a], c.vertices) - u) < 0.0) std::swap(a, b);
    auto angle = [&](const Points& p) {
      const Vec3 na = oriented_normal(c.faces[a], p, c.vertices), nb = oriented_normal(c.faces[b], p, c.vertices);
      const Vec3 e = (p[edge.second] - p[edge.first]).normalized();
      return -std::atan2(na.cross(nb).dot(e), na.dot(nb));  // valley > 0
    };
    double degrees = angle(*x) * 180.0 / std::numbers::pi;
    const double theta = angle(*near);
    if (theta > flat_tolerance) {
      c.assignment.push_back('V');
      ++c.valleys;
      if (!(degrees > 0.0)) c.contradicted.push_back(c.edges.size() - 1);
    } else if (theta < -flat_tolerance) {
      c.assignment.push_back('M');
      ++c.mountains;
      if (!(degrees < 0.0)) c.contradicted.push_back(c.edges.size() - 1);
    } else {
      c.assignment.push_back('F');
      if (std::abs(degrees) < 1e-6) {
        degrees = 0.0;  // FOLD 1.2: a flat crease has fold angle 0
      } else {
        c.contradicted.push_back(c.edges.size() - 1);
      }
    }
    c.fold_angle.push_back(degrees);
  }
  return c;
}

CreaseDrawing crease_drawing(const CreasePattern& c, std::optional<double> scale) {
  if (scale && !(*scale > 0.0 && std::isfinite(*scale))) {
    throw InvalidInputError("--scale", "must be a positive number of millimetres per model unit");
  }
  double lo_x = 0.0, hi_x = 0.0, lo_z = c.vertices.front().y(), hi_z = lo_z;
  for (const Vec2& p : c.vertices) {
    lo_x = std::min(lo_x, p.x()), hi_x = std::max(hi_x, p.x());
    lo_z = std::min(lo_z, p.y()), hi_z = std::max(hi_z, p.y());
  }
  for (double z : c.apex_heights) lo_z = std::min(lo_z, z), hi_z = std::max(hi_z, z);
  const double w = std::max(hi_x - lo_x, 1e-9), h = std::max(hi_z - lo_z, 1e-9);
  CreaseDrawing d;
  d.scale = scale ? *scale : std::min(170.0 / w, 220.0 / h);
  if (const double across = std::max(w, h) * d.scale; !(across <= 1e7)) {
    throw InvalidInputError("--scale", "the pattern would be " + format_significant(across) +
                                           " mm across: more than 10 km (a smaller --scale)");
  }
  // Margins: 12 mm left (apex names beside the axis), 10 mm elsewhere; 30 mm header, 10 mm footer.
  const double left = 12.0, margin = 10.0, header = 30.0, footer = 10.0;
  d.size = Vec2(std::max(w * d.scale + left + margin, 190.0), h * d.scale + header + footer + 2.0 * margin);
  auto at = [&](double x, double z) { return Vec2(left + (x - lo_x) * d.scale, margin + footer + (z - lo_z) * d.scale); };
  SheetPage& page = d.page;
  page.lines.push_back(SheetLine{at(0.0, lo_z), at(0.0, hi_z), LineStyle::axis});
  bool any_flat = false;
  for (std::size_t k = 0; k < c.edges.size(); ++k) {
    const Vec2 a = c.vertices[c.edges[k][0]], b = c.vertices[c.edges[k][1]];
    const char m = c.assignment[k];
    const LineStyle style = m == 'M' ? LineStyle::mountain : m == 'V' ? LineStyle::valley : m == 'B' ? LineStyle::cut : LineStyle::flat;
    any_flat = any_flat || m == 'F';
    page.lines.push_back(SheetLine{at(a.x(), a.y()), at(b.x(), b.y()), style});
  }
  for (std::size_t j = 0; j < c.apex_heights.size(); ++j) {
    const Vec2 p = at(0.0, c.apex_heights[j]);
    page.fills.push_back(SheetFill{{p + Vec2(-0.6, -0.6), p + Vec2(0.6, -0.6), p + Vec2(0.6, 0.6), p + Vec2(-0.6, 0.6)},
                                   FillStyle::marker, std::nullopt});
    const std::string name = "A" + std::to_string(j);
    add_text(page, name, p + Vec2(-1.5 - text_width(name, 1.6), -0.8), 1.6, TextRole::note);
  }
  const double top = d.size.y() - margin, right = d.size.x() - margin;
  add_text(page, c.name + ": crease pattern", Vec2(margin, top - 4.0), 4.0, TextRole::title);
  char folded[160];
  std::snprintf(folded, sizeof folded, "%zu mountain and %zu valley creases, folding towards t = %.6g; x: distance from the axis, z: height", c.mountains, c.valleys, c.t);
  add_text(page, folded, Vec2(margin, top - 10.0), 2.2, TextRole::note);
  Legend legend(page, margin, right, top - 16.0);
  legend.line(LineStyle::mountain, "mountain fold (away from you)");
  legend.line(LineStyle::valley, "valley fold (towards you)");
  legend.line(LineStyle::cut, "boundary (cut)");
  if (any_flat) legend.line(LineStyle::flat, "crease that stays flat");
  legend.line(LineStyle::axis, "the axis (x = 0)");
  legend.fill(FillStyle::marker, "A0, A1, ...: the apex of each profile, on the axis");
  add_scale_bar(page, Vec2(margin, margin), d.scale, std::min(50.0, 0.4 * (right - margin)));
  return d;
}

std::string crease_svg(const CreasePattern& c, std::optional<double> scale) {
  const CreaseDrawing d = crease_drawing(c, scale);
  return page_svg(d.page, d.size, c.name + ": crease pattern, " + std::to_string(c.mountains) + " mountain, " +
                                      std::to_string(c.valleys) + " valley creases (folded towards t = " +
                                      format_number(c.t) + "), mm");
}

std::string crease_pdf(const CreasePattern& c, std::optional<double> scale) {
  const CreaseDrawing d = crease_drawing(c, scale);
  return pages_pdf({d.page}, d.size, c.name + ": crease pattern");
}

nlohmann::json crease_fold(const CreasePattern& c) {
  nlohmann::json vertices = nlohmann::json::array(), faces = nlohmann::json::array(), edges = nlohmann::json::array(),
                 assignment = nlohmann::json::array(), angles = nlohmann::json::array();
  for (const Vec2& p : c.vertices) vertices.push_back({p.x(), p.y()});
  for (const Quad& q : c.faces) faces.push_back({q[0], q[1], q[2], q[3]});
  for (std::size_t k = 0; k < c.edges.size(); ++k) {
    edges.push_back({c.edges[k][0], c.edges[k][1]});
    assignment.push_back(std::string(1, c.assignment[k]));
    if (!std::isfinite(c.fold_angle[k])) throw Error(ExitCode::internal, "a fold angle is not finite");
    angles.push_back(c.fold_angle[k]);
  }
  return {{"file_spec", 1.2},
          {"file_creator", "phedra"},
          {"file_title", c.name},
          {"file_classes", {"singleModel"}},
          {"frame_classes", {"creasePattern"}},
          {"frame_attributes", {"2D"}},
          {"frame_title", "developed P-hedron: x = distance from the axis, y = height along it"},
          {"phedra:folded_t", c.t},
          {"vertices_coords", vertices},
          {"faces_vertices", faces},
          {"edges_vertices", edges},
          {"edges_assignment", assignment},
          {"edges_foldAngle", angles}};
}

}  // namespace phedra
