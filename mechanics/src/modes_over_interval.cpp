#include "phedra/modes_over_interval.h"
#include "phedra/report_values.h"

#include "phedra/errors.h"
#include "phedra/interval_check.h"
#include "phedra/number_format.h"

#include <algorithm>
#include <cmath>

namespace phedra {
ModesOverInterval modes_over_interval(const Design& design, std::size_t count, const StiffnessOptions& options,
                                      std::size_t modes) {
  if (count < 2) throw InvalidInputError("--over-interval", "needs at least 2 configurations (both limits), got " + std::to_string(count));
  const Assembly& a = design.assembly;
  ModesOverInterval out;
  out.name = a.name();
  out.panels = to_string(options.panels);
  out.t_lambda = a.flexion_interval().lower.t;
  out.t_mu = a.flexion_interval().upper.t;
  Eigen::MatrixXd previous;
  std::size_t previous_nodes = 0;
  for (double t : interval_samples(out.t_lambda, out.t_mu, count)) {
    const ModeAnalysis m = analyze_modes(design, t, options, modes);
    ModesAt at;
    at.t = t;
    at.rigid_body_modes = m.rigid_body_modes;
    at.eigenvalues.assign(m.eigenvalues.data(), m.eigenvalues.data() + m.eigenvalues.size());
    at.gap = m.gap;
    at.motion_alignment = m.motion_alignment;
    at.motion_stiffness = m.motion_stiffness;
    const std::size_t k = at.eigenvalues.size();
    at.track.assign(k, 0);
    if (!out.configurations.empty() && previous_nodes == m.nodes) {
      // Greedy matching on the overlaps, largest first.
      const Eigen::MatrixXd overlap = (previous.transpose() * m.modes).cwiseAbs();
      const ModesAt& before = out.configurations.back();
      std::vector<bool> used(static_cast<std::size_t>(overlap.rows()), false);
      std::vector<std::pair<double, std::pair<Eigen::Index, Eigen::Index>>> pairs;
      for (Eigen::Index i = 0; i < overlap.rows(); ++i)
        for (Eigen::Index j = 0; j < overlap.cols(); ++j) pairs.push_back({overlap(i, j), {i, j}});
      std::sort(pairs.begin(), pairs.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
      for (const auto& [value, ij] : pairs) {
        const auto [i, j] = ij;
        if (value < 0.5) break;
        if (used[static_cast<std::size_t>(i)] || at.track[static_cast<std::size_t>(j)] != 0) continue;
        used[static_cast<std::size_t>(i)] = true;
        at.track[static_cast<std::size_t>(j)] = before.track[static_cast<std::size_t>(i)];
      }
      // Crossings: two tracks in both configurations whose order changed.
      for (std::size_t x = 0; x < k; ++x) {
        for (std::size_t y = x + 1; y < k; ++y) {
          const std::size_t tx = at.track[x], ty = at.track[y];
          if (tx == 0 || ty == 0) continue;
          const auto px = std::find(before.track.begin(), before.track.end(), tx);
          const auto py = std::find(before.track.begin(), before.track.end(), ty);
          if (px > py) out.crossings.push_back({before.t, t, ty, tx});
        }
      }
    }
    for (std::size_t& track : at.track) {
      if (track == 0) track = ++out.tracks;
    }
    previous = m.modes;
    previous_nodes = m.nodes;
    out.configurations.push_back(std::move(at));
  }
  return out;
}

nlohmann::json ModesOverInterval::to_json() const {
  nlohmann::json list = nlohmann::json::array();
  for (const ModesAt& c : configurations) {
    list.push_back({{"t", c.t},
                    {"rigid_body_modes", c.rigid_body_modes},
                    {"eigenvalues", c.eigenvalues},
                    {"tracks", c.track},
                    {"gap", optional_json(c.gap)},
                    {"motion_alignment", optional_json(c.motion_alignment)},
                    {"motion_stiffness", optional_json(c.motion_stiffness)}});
  }
  nlohmann::json crossing_list = nlohmann::json::array();
  for (const ModeCrossing& c : crossings) {
    crossing_list.push_back({{"between", {c.after_t, c.before_t}}, {"tracks", {c.track_a, c.track_b}}});
  }
  return {{"name", name},         {"panels", panels}, {"t_lambda", t_lambda}, {"t_mu", t_mu},
          {"configurations", list}, {"crossings", crossing_list}, {"tracks", tracks}};
}

std::string ModesOverInterval::to_csv() const {
  std::size_t modes = 0;
  for (const ModesAt& c : configurations) modes = std::max(modes, c.eigenvalues.size());
  std::string out = "t,rigid_body_modes,gap,motion_alignment,motion_stiffness";
  for (std::size_t k = 1; k <= modes; ++k) out += ",eigenvalue_" + std::to_string(k) + ",track_" + std::to_string(k);
  out += "\n";
  for (const ModesAt& c : configurations) {
    out += format_number(c.t) + "," + std::to_string(c.rigid_body_modes) + "," + csv_number(c.gap) + "," +
           csv_number(c.motion_alignment) + "," + csv_number(c.motion_stiffness);
    for (std::size_t k = 0; k < modes; ++k) {
      out += k < c.eigenvalues.size() ? "," + format_number(c.eigenvalues[k]) + "," + std::to_string(c.track[k]) : ",,";
    }
    out += "\n";
  }
  return out;
}

}  // namespace phedra
