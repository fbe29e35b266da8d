#include "phedra/crease_pattern.h"

#include "phedra/errors.h"
#include "phedra/number_format.h"

#include <cmath>
#include <map>
#include <numbers>
#include <sstream>

namespace phedra {
namespace {

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

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

std::string crease_svg(const CreasePattern& c) {
  double lo_x = 0.0, hi_x = 0.0, lo_z = c.vertices.front().y(), hi_z = lo_z;
  for (const Vec2& p : c.vertices) {
    lo_x = std::min(lo_x, p.x());
    hi_x = std::max(hi_x, p.x());
    lo_z = std::min(lo_z, p.y());
    hi_z = std::max(hi_z, p.y());
  }
  for (double z : c.apex_heights) lo_z = std::min(lo_z, z), hi_z = std::max(hi_z, z);
  const double span = std::max(hi_x - lo_x, hi_z - lo_z), margin = 0.05 * span, stroke = 0.004 * span;
  auto X = [&](double x) { return format_number(x - lo_x + margin); };
  auto Y = [&](double z) { return format_number(hi_z - z + margin); };
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " << format_number(hi_x - lo_x + 2 * margin) << ' '
      << format_number(hi_z - lo_z + 2 * margin) << "\" width=\"800\">\n<title>" << c.name << ": crease pattern, "
      << c.mountains << " mountain, " << c.valleys << " valley creases (folded towards t = " << format_number(c.t)
      << ")</title>\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  // The axis and its apexes.
  svg << "<line x1=\"" << X(0) << "\" y1=\"" << Y(hi_z + margin) << "\" x2=\"" << X(0) << "\" y2=\"" << Y(lo_z - margin)
      << "\" stroke=\"#999\" stroke-width=\"" << format_number(stroke * 0.5) << "\" stroke-dasharray=\""
      << format_number(stroke * 2) << "\"/>\n";
  for (std::size_t j = 0; j < c.apex_heights.size(); ++j) {
    svg << "<circle class=\"apex\" cx=\"" << X(0) << "\" cy=\"" << Y(c.apex_heights[j]) << "\" r=\""
        << format_number(stroke * 1.5) << "\" fill=\"#999\"><title>S_" << j << "</title></circle>\n";
  }
  for (std::size_t k = 0; k < c.edges.size(); ++k) {
    const Vec2 a = c.vertices[c.edges[k][0]], b = c.vertices[c.edges[k][1]];
    const char m = c.assignment[k];
    const char* colour = m == 'M' ? "#d62728" : m == 'V' ? "#1f77b4" : m == 'B' ? "black" : "#999";
    svg << "<line class=\"" << m << "\" x1=\"" << X(a.x()) << "\" y1=\"" << Y(a.y()) << "\" x2=\"" << X(b.x())
        << "\" y2=\"" << Y(b.y()) << "\" stroke=\"" << colour << "\" stroke-width=\"" << format_number(stroke) << "\"";
    if (m == 'M') svg << " stroke-dasharray=\"" << format_number(stroke * 6) << ' ' << format_number(stroke * 2) << ' '
                      << format_number(stroke) << ' ' << format_number(stroke * 2) << "\"";
    if (m == 'V') svg << " stroke-dasharray=\"" << format_number(stroke * 4) << ' ' << format_number(stroke * 2) << "\"";
    svg << "/>\n";
  }
  svg << "</svg>\n";
  return svg.str();
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
