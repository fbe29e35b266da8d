#include "phedra/mechanics_charts.h"

#include "phedra/number_format.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>

namespace phedra {

Chart energy_chart(const EnergyLandscape& e) {
  Chart chart;
  chart.title = e.name + ": the energy of the exact motion";
  chart.subtitle = "fold springs at rest at t = " + format_significant(e.rest_t) + " (" + std::to_string(e.folds) + " folds); " +
                   (e.bistable() ? "bistable: barrier " + format_significant(*e.barrier) + ", back " + format_significant(*e.reverse_barrier)
                                 : "one minimum (the rest state)");
  chart.x_label = "motion parameter t (flexion interval [" + format_significant(e.t_lambda) + ", " + format_significant(e.t_mu) + "])";
  chart.x_lo = e.t_lambda;
  chart.x_hi = e.t_mu;
  ChartSeries energy{"E(t)", {}, {}, 0, false}, rate{"dE/dt", {}, {}, 3, false}, zero{"", {e.t_lambda, e.t_mu}, {0.0, 0.0}, 7, true};
  for (const EnergySample& s : e.samples) {
    energy.x.push_back(s.t), energy.y.push_back(s.energy);
    rate.x.push_back(s.t), rate.y.push_back(s.rate);
  }
  ChartPanel top{"Energy E(t) = sum of 1/2 L KF (theta - theta_rest)^2 over the folds", "E (model units)", {}, "", false,
                 {energy}, {}, {{e.rest_t, "rest", true}}, {}, {}};
  ChartPanel middle{"Generalized force dE/dt (zero at every equilibrium)", "dE/dt", {}, "", false, {zero, rate}, {}, {}, {}, {}};
  for (const Equilibrium& q : e.equilibria) {
    const MarkerShape shape = q.rest ? MarkerShape::diamond : q.minimum ? MarkerShape::dot : MarkerShape::triangle_up;
    const int colour = q.rest ? 4 : q.minimum ? 2 : 1;
    const std::string label = q.rest ? "" : (q.minimum ? "min " : "max ") + format_significant(q.t, 4);
    top.markers.push_back({q.t, q.energy, shape, colour, label});
    middle.markers.push_back({q.t, 0.0, shape, colour, ""});
  }
  top.marker_legend = {{MarkerShape::diamond, "rest state"}, {MarkerShape::dot, "minimum"}, {MarkerShape::triangle_up, "maximum"}};
  middle.marker_legend = top.marker_legend;
  chart.panels = {top, middle};

  // Force against stroke: L_k / L_k(rest), forces clipped where they pass through a pole.
  const auto rest = std::find_if(e.samples.begin(), e.samples.end(), [&](const EnergySample& s) { return s.t == e.rest_t; });
  ChartPanel force{"Force that holds an extension along axis k: dE/dt over dL_k/dt", "force (energy / length)",
                   std::nullopt, "stroke L_k / L_k(rest)", false, {}, {}, {}, {}, {}};
  double lo = INFINITY, hi = -INFINITY;
  std::vector<double> magnitudes;
  for (const EnergySample& s : e.samples)
    for (const auto& f : s.force)
      if (f) magnitudes.push_back(std::abs(*f));
  std::sort(magnitudes.begin(), magnitudes.end());
  const double clip = magnitudes.empty() ? 0.0 : 4.0 * magnitudes[magnitudes.size() * 9 / 10];
  bool clipped = false;
  for (int k = 0; k < 3; ++k) {
    if (rest == e.samples.end() || !rest->length[k] || !(*rest->length[k] > 0.0)) continue;
    ChartSeries series{"axis " + std::to_string(k + 1), {}, {}, k, false};
    bool any = false;
    for (const EnergySample& s : e.samples) {
      if (!s.length[k]) continue;
      const double stroke = *s.length[k] / *rest->length[k];
      series.x.push_back(stroke);
      std::optional<double> f = s.force[k];
      if (f && std::abs(*f) > clip) f.reset(), clipped = true;
      series.y.push_back(f);
      any = any || f.has_value();
      lo = std::min(lo, stroke), hi = std::max(hi, stroke);
    }
    if (any) force.series.push_back(series);
  }
  if (!force.series.empty() && hi > lo) {
    force.x_range = std::pair{lo, hi};
    if (clipped) force.notes = {"beyond +-" + format_significant(clip, 3) + " not drawn", "(poles: dL_k/dt = 0)"};
    chart.panels.push_back(force);
  }
  return chart;
}

Chart modes_chart(const ModesOverInterval& m) {
  Chart chart;
  chart.title = m.name + ": the softest modes over the flexion interval (" + m.panels + ")";
  chart.subtitle = std::to_string(m.configurations.size()) + " configurations, " + std::to_string(m.tracks) +
                   " tracked modes, " + std::to_string(m.crossings.size()) + " crossings";
  chart.x_label = "motion parameter t";
  chart.x_lo = m.t_lambda;
  chart.x_hi = m.t_mu;
  std::map<std::size_t, ChartSeries> tracks;
  ChartSeries gap{"gap lambda_2 / lambda_1", {}, {}, 0, false};
  ChartSeries alignment{"|cos(mode 1, dX/dt)|", {}, {}, 2, false};
  for (const ModesAt& c : m.configurations) {
    for (auto& [id, series] : tracks) {  // a track that is not here has a gap
      if (std::find(c.track.begin(), c.track.end(), id) == c.track.end()) series.x.push_back(c.t), series.y.push_back(std::nullopt);
    }
    for (std::size_t k = 0; k < c.eigenvalues.size(); ++k) {
      ChartSeries& s = tracks[c.track[k]];
      if (s.label.empty()) s = {"mode " + std::to_string(c.track[k]), {}, {}, static_cast<int>(c.track[k] - 1), false};
      s.x.push_back(c.t);
      s.y.push_back(c.eigenvalues[k]);
    }
    gap.x.push_back(c.t), gap.y.push_back(c.gap);
    alignment.x.push_back(c.t), alignment.y.push_back(c.motion_alignment);
  }
  ChartPanel eigen{"Smallest non-rigid eigenvalues of the tangent stiffness (unit mass)", "eigenvalue", {}, "", true,
                   {}, {}, {}, {}, {}};
  std::size_t shown = 0;
  for (auto& [id, series] : tracks) {
    if (shown++ >= 10) series.label.clear();  // the legend keeps the first ten
    eigen.series.push_back(series);
  }
  if (tracks.size() > 10) {  // drawn in the palette's ten colours again: say so beside the legend
    const std::size_t first_unlisted = std::next(tracks.begin(), 10)->first;
    eigen.notes.push_back("modes " + std::to_string(first_unlisted) + "-" + std::to_string(tracks.rbegin()->first) +
                          " drawn, not listed:");
    eigen.notes.push_back("their colours are those of");
    eigen.notes.push_back("modes " + std::to_string(first_unlisted - 10) + "-" + std::to_string(tracks.rbegin()->first - 10));
  }
  for (const ModeCrossing& c : m.crossings) {
    // Where the two tracks meet: between the configurations, at their mean value.
    double value = 0.0;
    int count = 0;
    for (const ModesAt& at : m.configurations) {
      if (at.t != c.before_t) continue;
      for (std::size_t k = 0; k < at.track.size(); ++k) {
        if (at.track[k] == c.track_a || at.track[k] == c.track_b) value += at.eigenvalues[k], ++count;
      }
    }
    if (count) eigen.markers.push_back({0.5 * (c.after_t + c.before_t), value / count, MarkerShape::diamond, 7, ""});
  }
  if (!m.crossings.empty()) eigen.marker_legend = {{MarkerShape::diamond, "crossing"}};
  ChartPanel gap_panel{"Gap: the second non-rigid eigenvalue over the first", "gap", {}, "", true, {gap}, {}, {}, {}, {}};
  ChartPanel align_panel{"How the first mode aligns with the exact motion dX/dt", "|cos|", {}, "", false, {alignment}, {}, {}, {}, {}};
  chart.panels = {eigen, gap_panel, align_panel};
  return chart;
}

}  // namespace phedra
