#include "phedra/mechanics_figures.h"

#include "phedra/energy_landscape.h"
#include "phedra/errors.h"
#include "phedra/stiffness_modes.h"

#include <algorithm>
#include <cmath>

namespace phedra {

const std::vector<std::string>& mechanics_figure_names() {
  static const std::vector<std::string> names{"mechanics.gap", "mechanics.motion_stiffness", "mechanics.bistable",
                                              "mechanics.barrier"};
  return names;
}

bool is_mechanics_figure(const std::string& name) {
  const std::vector<std::string>& n = mechanics_figure_names();
  return std::find(n.begin(), n.end(), name) != n.end();
}

std::optional<double> MechanicsFigures::figure(const std::string& name) const {
  if (name == "mechanics.gap") return gap;
  if (name == "mechanics.motion_stiffness") return motion_stiffness;
  if (name == "mechanics.bistable") return bistable ? 1.0 : 0.0;
  if (name == "mechanics.barrier") return barrier;
  throw InvalidInputError("figure", "unknown figure \"" + name + "\"");
}

StiffnessOptions default_stiffness(const Design& design) {
  StiffnessOptions o;
  try {
    BarHingeModel(design, design.assembly.evaluate(design.assembly.t_star()), o);
  } catch (const InvalidInputError&) {
    o.panels = PanelModel::n4b5;
  }
  return o;
}

MechanicsFigures mechanics_figures(const Design& design, const std::vector<std::string>& names) {
  MechanicsFigures f;
  auto wants = [&](const char* a, const char* b) {
    return std::find(names.begin(), names.end(), a) != names.end() || std::find(names.begin(), names.end(), b) != names.end();
  };
  const Assembly& a = design.assembly;
  const StiffnessOptions options = default_stiffness(design);
  if (wants("mechanics.gap", "mechanics.motion_stiffness")) {
    const ModeAnalysis m = analyze_modes(design, a.t_star(), options, 2);
    f.gap = m.gap;
    f.motion_stiffness = m.motion_stiffness;
  }
  if (wants("mechanics.bistable", "mechanics.barrier")) {
    EnergyOptions e;
    e.rest_t = a.t_star();
    e.samples = 101;
    e.stiffness = options;
    const EnergyLandscape l = energy_landscape(design, e);
    f.bistable = l.bistable();
    f.barrier = l.barrier;
    // Walking away from the rest state on each side: the most falling dE/dt, then the most rising after it.
    const double scale = std::max(l.largest_energy, 1e-300) / (l.t_mu - l.t_lambda);
    double best = -INFINITY;
    for (int side : {-1, 1}) {
      std::vector<double> away;  // (t - T0) sign times dE/dt, outwards
      for (const EnergySample& s : l.samples) {
        if (s.rate && (s.t - l.rest_t) * side > 0.0) away.push_back(side * *s.rate);
      }
      if (side < 0) std::reverse(away.begin(), away.end());
      if (away.empty()) continue;
      const auto dip = std::min_element(away.begin(), away.end());
      const double rise = dip + 1 == away.end() ? *dip : *std::max_element(dip + 1, away.end());
      best = std::max(best, std::min(-*dip, rise) / scale);
    }
    f.bistability = std::isfinite(best) ? best : -1.0;
  }
  return f;
}

}  // namespace phedra
