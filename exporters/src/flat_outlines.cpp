#include "phedra/flat_outlines.h"

#include "phedra/assembly_mesh.h"
#include "phedra/errors.h"
#include "phedra/number_format.h"
#include "phedra/panel_shape.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>

namespace phedra {
namespace {

/// The panel in its own plane: corner 0 at the origin, edge 0 along +x, turning counter-clockwise.
std::array<Vec2, 4> unfold(const std::array<Vec3, 4>& p) {
  Vec3 normal = Vec3::Zero();
  for (int k = 0; k < 4; ++k) {
    const Vec3 c = (p[k] - p[(k + 3) % 4]).cross(p[(k + 1) % 4] - p[k]);
    normal += c;  // the vector area (x 2): orientation of the panel
  }
  if (normal.squaredNorm() == 0.0) normal = (p[1] - p[0]).cross(p[2] - p[0]);
  Vec3 u = p[1] - p[0];
  if (u.squaredNorm() == 0.0) u = p[2] - p[0];
  u.normalize();
  const Vec3 v = normal.normalized().cross(u);
  std::array<Vec2, 4> out;
  for (int k = 0; k < 4; ++k) out[k] = Vec2(u.dot(p[k] - p[0]), v.dot(p[k] - p[0]));
  return out;
}

Vec2 centroid(const FlatPanel& p) { return 0.25 * (p.corners[0] + p.corners[1] + p.corners[2] + p.corners[3]); }

std::string n(double x) { return format_number(std::abs(x) < 1e-12 ? 0.0 : x); }

}  // namespace

std::array<Vec2, 4> OutlineSheet::tab_polygon(const FlatPanel& p, int k) const {
  const Vec2 a = p.corners[k], b = p.corners[(k + 1) % 4];
  const Vec2 along = b - a;
  // Outward: away from the panel's centroid.
  Vec2 out(along.y(), -along.x());
  if (out.dot(centroid(p) - a) > 0.0) out = -out;
  out.normalize();
  const double depth = tab_depth * along.norm();
  const Vec2 unit = along.normalized();
  return {a, a + depth * (out + unit), b + depth * (out - unit), b};
}

OutlineSheet flat_outlines(const Design& design, const OutlineOptions& options) {
  if (!(options.tab_depth > 0.0 && options.tab_depth < 0.5)) {
    throw InvalidInputError("--tab-depth", "must lie in (0, 0.5) of the hinge length");
  }
  if (!(options.spacing >= 0.0)) throw InvalidInputError("--spacing", "must not be negative");
  if (!(options.scale > 0.0) || !std::isfinite(options.scale)) throw InvalidInputError("--scale", "must be positive");
  const Assembly& a = design.assembly;
  const AssemblyMesh mesh = panel_mesh(design);
  const Points x = mesh.positions(a.evaluate(a.t_star()));
  OutlineSheet sheet;
  sheet.name = a.name();
  sheet.tab_depth = options.tab_depth;
  // Hinges: edges of two or more panels, numbered in the order met.
  std::map<std::pair<std::size_t, std::size_t>, std::vector<std::pair<std::size_t, int>>> edges;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    for (int k = 0; k < 4; ++k) {
      const std::size_t u = mesh.faces[f][k], v = mesh.faces[f][(k + 1) % 4];
      if (u == v || (x[u] - x[v]).norm() <= 1e-12 * a.model_size()) continue;  // a collapsed edge: no hinge
      edges[{std::min(u, v), std::max(u, v)}].push_back({f, k});
    }
  }
  sheet.panels.resize(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    FlatPanel& p = sheet.panels[f];
    const Quad& q = mesh.faces[f];
    const std::size_t m = mesh.face_member[f], columns = a.topology(m).face_columns();
    p.face = f;
    p.member = m;
    p.row = mesh.face_local[f] / columns;
    p.column = mesh.face_local[f] % columns;
    p.corners = unfold({x[q[0]], x[q[1]], x[q[2]], x[q[3]]});
    for (Vec2& c : p.corners) c *= options.scale;
    // The same classification as every report (panel_shape.h).
    p.shape = panel_shape({x[q[0]], x[q[1]], x[q[2]], x[q[3]]});
  }
  std::vector<std::pair<std::size_t, std::size_t>> ordered;
  for (const auto& [edge, faces] : edges) {
    if (faces.size() >= 2) ordered.push_back(edge);
  }
  std::sort(ordered.begin(), ordered.end(), [&](const auto& e1, const auto& e2) {
    return edges[e1].front() < edges[e2].front();
  });
  for (const auto& edge : ordered) {
    const auto& faces = edges[edge];
    const std::size_t id = sheet.hinges++;
    for (const auto& [f, k] : faces) sheet.panels[f].hinge[k] = id;
    if (options.tabs) sheet.panels[faces.front().first].tab[faces.front().second] = true;
  }
  // Shelf layout: tallest first, rows of about the square root of the total area.
  double area = 0.0;
  std::vector<std::pair<Vec2, Vec2>> boxes(sheet.panels.size());
  for (std::size_t f = 0; f < sheet.panels.size(); ++f) {
    const FlatPanel& p = sheet.panels[f];
    Vec2 lo = p.corners[0], hi = p.corners[0];
    auto grow = [&](const Vec2& c) {
      lo = lo.cwiseMin(c);
      hi = hi.cwiseMax(c);
    };
    for (const Vec2& c : p.corners) grow(c);
    for (int k = 0; k < 4; ++k) {
      if (p.tab[k]) {
        for (const Vec2& c : sheet.tab_polygon(p, k)) grow(c);
      }
    }
    boxes[f] = {lo, hi};
    area += (hi - lo).prod();
  }
  const double gap = options.spacing * a.model_size() * options.scale;
  double widest = 0.0;
  for (const auto& [lo, hi] : boxes) widest = std::max(widest, hi.x() - lo.x());
  const double row_width = std::max(widest, 1.5 * std::sqrt(area));
  std::vector<std::size_t> order(sheet.panels.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    return boxes[i].second.y() - boxes[i].first.y() > boxes[j].second.y() - boxes[j].first.y();
  });
  double cx = gap, cy = gap, shelf = 0.0;
  for (std::size_t f : order) {
    const Vec2 size = boxes[f].second - boxes[f].first;
    if (cx > gap && cx + size.x() > row_width + gap) {
      cx = gap;
      cy += shelf + gap;
      shelf = 0.0;
    }
    const Vec2 shift = Vec2(cx, cy) - boxes[f].first;
    for (Vec2& c : sheet.panels[f].corners) c += shift;
    cx += size.x() + gap;
    shelf = std::max(shelf, size.y());
    sheet.width = std::max(sheet.width, cx);
  }
  sheet.height = cy + shelf + gap;
  sheet.label_size = 0.025 * a.model_size() * options.scale;
  for (const FlatPanel& p : sheet.panels) {
    for (const Vec2& c : p.corners) {
      if (!c.allFinite()) throw Error(ExitCode::internal, "outline of panel " + std::to_string(p.face) + " is not finite");
    }
  }
  return sheet;
}

std::string outlines_svg(const OutlineSheet& s) {
  std::ostringstream svg;
  // y grows downwards in SVG: flip, so the outlines are not mirrored.
  auto X = [](const Vec2& p) { return n(p.x()); };
  auto Y = [&s](const Vec2& p) { return n(s.height - p.y()); };
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " << n(s.width) << ' ' << n(s.height)
      << "\" width=\"" << n(s.width) << "mm\" height=\"" << n(s.height) << "mm\">\n"
      << "<title>" << s.name << ": " << s.panels.size() << " panels, " << s.hinges
      << " hinges, sizes in mm</title>\n"
      << "<g fill=\"none\" stroke=\"black\" stroke-width=\"" << n(s.label_size * 0.08) << "\">\n";
  for (const FlatPanel& p : s.panels) {
    // Cut edges solid, edges under a tab dashed (fold there).
    svg << "<g id=\"panel-" << p.face << "\"" << (p.cuttable() ? "" : " stroke=\"red\"") << ">";
    for (int k = 0; k < 4; ++k) {
      const Vec2 a = p.corners[k], b = p.corners[(k + 1) % 4];
      svg << "<line x1=\"" << X(a) << "\" y1=\"" << Y(a) << "\" x2=\"" << X(b) << "\" y2=\"" << Y(b) << "\""
          << (p.tab[k] ? " stroke-dasharray=\"" + n(s.label_size * 0.4) + "\"" : std::string()) << "/>";
      if (!p.tab[k]) continue;
      svg << "<polyline class=\"tab\" points=\"";
      for (const Vec2& c : s.tab_polygon(p, k)) svg << X(c) << ',' << Y(c) << ' ';
      svg << "\"/>";
    }
    svg << "</g>\n";
  }
  svg << "</g>\n<g font-family=\"sans-serif\" font-size=\"" << n(s.label_size) << "\" text-anchor=\"middle\">\n";
  for (const FlatPanel& p : s.panels) {
    const Vec2 c = centroid(p);
    svg << "<text x=\"" << X(c) << "\" y=\"" << Y(c) << "\">P" << p.face << (p.cuttable() ? std::string() : " (" + to_string(p.shape) + ")")
        << "</text>\n";
    for (int k = 0; k < 4; ++k) {
      if (!p.hinge[k]) continue;
      const Vec2 mid = 0.5 * (p.corners[k] + p.corners[(k + 1) % 4]);
      const Vec2 label = mid + 0.25 * (c - mid);
      svg << "<text x=\"" << X(label) << "\" y=\"" << Y(label) << "\" fill=\"#06c\">H" << *p.hinge[k] << "</text>\n";
    }
  }
  svg << "</g>\n</svg>\n";
  return svg.str();
}

std::string outlines_dxf(const OutlineSheet& s) {
  std::ostringstream dxf;
  auto line = [&](const std::string& layer, const Vec2& a, const Vec2& b) {
    dxf << "0\nLINE\n8\n" << layer << "\n10\n" << n(a.x()) << "\n20\n" << n(a.y()) << "\n30\n0\n11\n" << n(b.x())
        << "\n21\n" << n(b.y()) << "\n31\n0\n";
  };
  auto text = [&](const Vec2& at, const std::string& what) {
    dxf << "0\nTEXT\n8\nLABELS\n10\n" << n(at.x()) << "\n20\n" << n(at.y()) << "\n30\n0\n40\n" << n(s.label_size)
        << "\n1\n" << what << "\n72\n1\n11\n" << n(at.x()) << "\n21\n" << n(at.y()) << "\n31\n0\n";
  };
  dxf << "0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\nAC1009\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n";
  dxf << "0\nSECTION\n2\nTABLES\n0\nTABLE\n2\nLAYER\n70\n3\n";
  for (const auto& [layer, colour] : {std::pair{"CUT", 7}, {"FOLD", 5}, {"LABELS", 3}}) {
    dxf << "0\nLAYER\n2\n" << layer << "\n70\n0\n62\n" << colour << "\n6\nCONTINUOUS\n";
  }
  dxf << "0\nENDTAB\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n";
  for (const FlatPanel& p : s.panels) {
    for (int k = 0; k < 4; ++k) {
      const Vec2 a = p.corners[k], b = p.corners[(k + 1) % 4];
      if (p.tab[k]) {
        line("FOLD", a, b);
        const auto tab = s.tab_polygon(p, k);
        for (int e = 0; e < 3; ++e) line("CUT", tab[e], tab[e + 1]);
      } else {
        line("CUT", a, b);
      }
    }
    const Vec2 c = centroid(p);
    text(c, "P" + std::to_string(p.face));
    for (int k = 0; k < 4; ++k) {
      if (!p.hinge[k]) continue;
      const Vec2 mid = 0.5 * (p.corners[k] + p.corners[(k + 1) % 4]);
      text(mid + 0.25 * (c - mid), "H" + std::to_string(*p.hinge[k]));
    }
  }
  dxf << "0\nENDSEC\n0\nEOF\n";
  return dxf.str();
}

}  // namespace phedra
