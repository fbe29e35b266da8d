#include "phedra/panel_size.h"

#include "phedra/panel_nets.h"

#include <algorithm>
#include <cmath>

namespace phedra {

double quad_area(const PanelCorners& v) { return 0.5 * (v[2] - v[0]).cross(v[3] - v[1]).norm(); }

std::vector<PanelProportions> panel_proportions(const Points& x, const std::vector<Quad>& faces) {
  std::vector<PanelProportions> out(faces.size());
  std::vector<double> longest(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const Quad& q = faces[f];
    const PanelCorners c{x[q[0]], x[q[1]], x[q[2]], x[q[3]]};
    PanelProportions& p = out[f];
    for (int k = 0; k < 4; ++k) {
      const double e = (c[(k + 1) % 4] - c[k]).norm();
      if (e > p.longest_edge) {
        p.longest_edge = e;
        p.longest = k;
      }
    }
    p.aspect = p.longest_edge > 0.0 ? quad_area(c) / (p.longest_edge * p.longest_edge) : 0.0;
    longest[f] = p.longest_edge;
  }
  if (faces.empty()) return out;
  std::nth_element(longest.begin(), longest.begin() + longest.size() / 2, longest.end());
  const double median = longest[longest.size() / 2];
  for (PanelProportions& p : out) p.edge_ratio = median > 0.0 ? p.longest_edge / median : 1.0;
  return out;
}

double bounding_diagonal(const Points& x) {
  if (x.empty()) return 0.0;
  Vec3 lo = x[0], hi = x[0];
  for (const Vec3& p : x) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

std::vector<PanelShape> bounded_panel_shapes(const Assembly& a, const AssemblyMesh& mesh, const SizeBounds& bounds) {
  std::vector<PanelShape> shapes = panel_shapes(a, mesh);
  AssemblyConfiguration at_star;
  a.evaluate(a.t_star(), at_star);
  const std::vector<PanelProportions> proportions = panel_proportions(mesh.positions(at_star), mesh.faces);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (!is_valid_panel(shapes[f])) continue;
    if (bounds.max_edge_ratio > 0.0 && proportions[f].edge_ratio > bounds.max_edge_ratio) {
      shapes[f] = PanelShape::oversized;
    } else if (proportions[f].aspect < bounds.min_aspect) {
      shapes[f] = PanelShape::sliver;
    }
  }
  return shapes;
}

double bounded_model_size(const Design& design, const SizeBounds& bounds) {
  const Assembly& a = design.assembly;
  if (!(bounds.max_edge_ratio > 0.0)) return a.model_size();
  const AssemblyMesh mesh = panel_mesh(design);
  AssemblyConfiguration c;
  a.evaluate(a.t_star(), c);
  const Points x = mesh.positions(c);
  const std::vector<PanelProportions> p = panel_proportions(x, mesh.faces);
  Points kept;
  bool dropped = false;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (p[f].edge_ratio > bounds.max_edge_ratio) {
      dropped = true;
      continue;
    }
    for (std::size_t v : mesh.faces[f]) kept.push_back(x[v]);
  }
  return dropped && !kept.empty() ? bounding_diagonal(kept) : a.model_size();
}

}  // namespace phedra
