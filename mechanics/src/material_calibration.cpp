#include "material_calibration.h"

#include <cmath>
#include <map>

namespace phedra {

void calibrate_from_material(const Material& material, const std::vector<ModelPanel>& panels, const Points& x,
                             std::vector<Bar>& bars, std::vector<Hinge>& hinges) {
  const double e = material.youngs_modulus, nu = material.poisson, thickness = material.thickness;
  const double d = e * thickness * thickness * thickness / (12.0 * (1.0 - nu * nu));
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> bar_of;
  for (std::size_t b = 0; b < bars.size(); ++b) {
    bar_of[std::minmax(bars[b].nodes[0], bars[b].nodes[1])] = b;
    bars[b].stiffness = 0.0;
  }
  auto add_area = [&](std::size_t a, std::size_t b, double area) { bars[bar_of.at(std::minmax(a, b))].stiffness += e * area; };
  for (const ModelPanel& p : panels) {
    const std::vector<std::size_t>& v = p.corners;
    if (v.size() == 3) {
      const double perimeter = (x[v[1]] - x[v[0]]).norm() + (x[v[2]] - x[v[1]]).norm() + (x[v[0]] - x[v[2]]).norm();
      const double area = 0.5 * (x[v[1]] - x[v[0]]).cross(x[v[2]] - x[v[0]]).norm();
      for (std::size_t k = 0; k < 3; ++k) add_area(v[k], v[(k + 1) % 3], thickness * 2.0 * area / (perimeter * (1.0 - nu)));
      continue;
    }
    double edge[4];
    for (std::size_t k = 0; k < 4; ++k) edge[k] = (x[v[(k + 1) % 4]] - x[v[k]]).norm();
    const double w = 0.5 * (edge[0] + edge[2]), h = 0.5 * (edge[1] + edge[3]);
    const double across = thickness * std::abs(h * h - nu * w * w) / (2.0 * h * (1.0 - nu * nu));  // edges 0 and 2
    const double along = thickness * std::abs(w * w - nu * h * h) / (2.0 * w * (1.0 - nu * nu));   // edges 1 and 3
    const double spoke = thickness * nu * std::pow(h * h + w * w, 1.5) / (2.0 * h * w * (1.0 - nu * nu));
    for (std::size_t k = 0; k < 4; ++k) {
      add_area(v[k], v[(k + 1) % 4], k % 2 == 0 ? across : along);
      add_area(*p.centre, v[k], spoke);
    }
  }
  double fold_length_sum = 0.0;
  std::size_t folds = 0;
  for (const Hinge& h : hinges) {
    if (h.kind == HingeKind::fold) fold_length_sum += h.length, ++folds;
  }
  const double length_scale = material.length_scale ? *material.length_scale
                                                    : (folds > 0 ? 2.0 * fold_length_sum / static_cast<double>(folds) : 1.0);
  for (Hinge& h : hinges) {
    if (h.kind == HingeKind::fold) {
      const double k_l = d / length_scale, k_m = 0.55 * d * std::cbrt(h.length / thickness);
      h.stiffness = 1.0 / (1.0 / k_l + 1.0 / k_m) / h.length;
    } else {
      // The spoke's diagonal: this spoke and the opposite one (the centre lies on the diagonal).
      const ModelPanel& p = panels[h.panels[0]];
      const std::size_t corner = h.nodes[1];
      std::size_t k = 0;
      while (p.corners[k] != corner) ++k;
      const double diagonal = h.length + (x[p.corners[(k + 2) % 4]] - x[*p.centre]).norm();
      h.stiffness = d * std::cbrt(diagonal / thickness) / diagonal;
    }
  }
}

}  // namespace phedra
