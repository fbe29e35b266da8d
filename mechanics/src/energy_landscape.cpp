#include "phedra/energy_landscape.h"
#include "phedra/report_values.h"

#include "phedra/errors.h"
#include "phedra/interval_check.h"
#include "phedra/metamaterial_metrics.h"
#include "phedra/number_format.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace phedra {

FoldEnergy::FoldEnergy(const Design& design, double rest_t, const StiffnessOptions& options)
    : design_(design), model_(design, design.assembly.evaluate(rest_t), options) {
  rest_angles_.resize(model_.fold_count());
  for (std::size_t h = 0; h < rest_angles_.size(); ++h) rest_angles_[h] = model_.angle(h, model_.positions());
}

void FoldEnergy::angles_at(const Points& x, std::vector<double>& angles, const std::vector<double>& near) const {
  const std::vector<double>& reference = near.empty() ? rest_angles_ : near;
  angles.resize(rest_angles_.size());
  for (std::size_t h = 0; h < angles.size(); ++h) angles[h] = continuous_angle(model_.angle(h, x), reference[h]);
}

double FoldEnergy::energy(double t, std::vector<double>& angles, const std::vector<double>& near) const {
  design_.assembly.evaluate(t, configuration_);
  model_.node_positions(configuration_, nodes_);
  angles_at(nodes_, angles, near);
  double e = 0.0;
  for (std::size_t h = 0; h < angles.size(); ++h) {
    const Hinge& hinge = model_.hinges()[h];
    const double d = angles[h] - rest_angles_[h];
    e += 0.5 * hinge.stiffness * hinge.length * d * d;
  }
  return e;
}

std::pair<double, std::optional<double>> FoldEnergy::energy_and_rate(double t, std::vector<double>& angles,
                                                                    const std::vector<double>& near) const {
  std::vector<Points> rates;
  const bool finite = design_.assembly.evaluate_rate(t, configuration_, rates);
  model_.node_positions(configuration_, nodes_);
  angles_at(nodes_, angles, near);
  Points v;
  if (finite) model_.node_rates(rates, v);
  double e = 0.0, de = 0.0;
  for (std::size_t h = 0; h < angles.size(); ++h) {
    const Hinge& hinge = model_.hinges()[h];
    const double d = angles[h] - rest_angles_[h];
    const double k = hinge.stiffness * hinge.length;
    e += 0.5 * k * d * d;
    if (!finite || d == 0.0) continue;
    const std::array<Vec3, 4> g = hinge_angle_gradient(hinge_nodes(hinge, nodes_));
    double rate = 0.0;
    for (int n = 0; n < 4; ++n) rate += g[n].dot(v[hinge.nodes[n]]);
    de += k * d * rate;
  }
  return {e, finite ? std::optional<double>(de) : std::nullopt};
}

bool EnergyLandscape::bistable() const {
  return std::count_if(equilibria.begin(), equilibria.end(), [](const Equilibrium& e) { return e.minimum; }) >= 2;
}

namespace {

struct Point {
  double t;
  double energy;
  std::optional<double> rate;
  std::vector<double> angles;
};

/// E and dE/dt at `t`, the angles carried from `from` continuously: steps of at
/// most half a radian for any fold, halving the step where one turns faster.
Point carried(const FoldEnergy& f, const Point& from, double t, int depth = 0) {
  Point p{t, 0.0, std::nullopt, {}};
  std::tie(p.energy, p.rate) = f.energy_and_rate(t, p.angles, from.angles);
  double turn = 0.0;
  for (std::size_t h = 0; h < p.angles.size(); ++h) turn = std::max(turn, std::abs(p.angles[h] - from.angles[h]));
  if (turn <= 0.5 || depth >= 30) return p;
  const Point middle = carried(f, from, 0.5 * (from.t + t), depth + 1);
  return carried(f, middle, t, depth + 1);
}

}  // namespace

EnergyLandscape energy_landscape(const Design& design, const EnergyOptions& options) {
  const Assembly& a = design.assembly;
  const double lo = a.flexion_interval().lower.t, hi = a.flexion_interval().upper.t;
  if (!(options.rest_t >= lo && options.rest_t <= hi)) {
    throw InvalidInputError("--rest-t", "the rest state t = " + format_number(options.rest_t) +
                                            " is outside the flexion interval [" + format_number(lo) + ", " +
                                            format_number(hi) + "]");
  }
  if (options.samples < 2) throw InvalidInputError("--samples", "must be at least 2 (both limits)");
  const FoldEnergy fold(design, options.rest_t, options.stiffness);
  EnergyLandscape out;
  out.name = a.name();
  out.rest_t = options.rest_t;
  out.t_lambda = lo;
  out.t_mu = hi;
  out.folds = fold.model().fold_count();

  std::vector<double> ts = interval_samples(lo, hi, options.samples);
  ts.push_back(options.rest_t);
  std::sort(ts.begin(), ts.end());
  ts.erase(std::unique(ts.begin(), ts.end()), ts.end());
  const std::size_t rest = static_cast<std::size_t>(std::find(ts.begin(), ts.end(), options.rest_t) - ts.begin());
  std::vector<Point> points(ts.size());
  points[rest] = {options.rest_t, 0.0, std::nullopt, fold.rest_angles()};
  std::tie(points[rest].energy, points[rest].rate) = fold.energy_and_rate(options.rest_t, points[rest].angles);
  for (std::size_t i = rest + 1; i < ts.size(); ++i) points[i] = carried(fold, points[i - 1], ts[i]);
  for (std::size_t i = rest; i-- > 0;) points[i] = carried(fold, points[i + 1], ts[i]);

  // The lengths of `phedra metrics` and the forces that hold them.
  const HomogenizedStrain strain(a, options.axes);
  out.axes = strain.axes();
  const std::array<double, 3> at_star = axis_extents(a.evaluate(a.t_star()).members, out.axes);
  for (const Point& p : points) {
    EnergySample s;
    s.t = p.t;
    s.energy = p.energy;
    s.rate = p.rate;
    const HomogenizedStrain::State state = strain.at(p.t);
    for (int k = 0; k < 3; ++k) {
      if (!state.stretch[k]) continue;
      s.length[k] = at_star[k] * *state.stretch[k];
      if (!p.rate || !state.rate[k]) continue;
      const double d_length = *s.length[k] * *state.rate[k];
      if (std::abs(d_length) * (hi - lo) > 1e-9 * *s.length[k]) s.force[k] = *p.rate / d_length;
    }
    out.largest_energy = std::max(out.largest_energy, p.energy);
    out.samples.push_back(s);
  }

  // Equilibria: the rest state, and every change of sign of dE/dt between samples.
  const double resolution = 1e-12 * (hi - lo);
  // At a flexion limit dE/dt is infinite, at the rest state zero: their signs
  // are the ones beside them, towards the other end of the pair, 1e-6 of the
  // interval away (closer, rounding in the positions, about 1e-15 of the model
  // size and more where the motion is ill-conditioned, can outweigh the rate).
  const double step = 1e-6 * (hi - lo);
  auto beside = [&](std::size_t i, double towards) {
    const bool moved = i == rest || !points[i].rate;
    return moved ? carried(fold, points[i], points[i].t + (towards > points[i].t ? step : -step)) : points[i];
  };
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    if (i == rest) out.equilibria.push_back({options.rest_t, true, points[i].energy, true});
    const Point left = beside(i, points[i + 1].t);
    const Point right = beside(i + 1, points[i].t);
    if (!left.rate || !right.rate) continue;
    const bool rises = *left.rate < 0.0 && *right.rate > 0.0, falls = *left.rate > 0.0 && *right.rate < 0.0;
    if (!rises && !falls) {
      if (*right.rate == 0.0 && i + 2 < points.size() && points[i + 2].rate) {
        const double after = *points[i + 2].rate;
        if ((*left.rate < 0.0 && after > 0.0) || (*left.rate > 0.0 && after < 0.0)) {
          out.equilibria.push_back({right.t, *left.rate < 0.0, right.energy, false});
        }
      }
      continue;
    }
    Point a_side = left;
    double b = right.t;
    while (b - a_side.t > resolution) {
      const Point m = carried(fold, a_side, 0.5 * (a_side.t + b));
      if (!m.rate || *m.rate == 0.0) {
        a_side = m;
        b = m.t;
        break;
      }
      if ((*m.rate < 0.0) == (*left.rate < 0.0)) {
        a_side = m;
      } else {
        b = m.t;
      }
    }
    const Point root = carried(fold, a_side, 0.5 * (a_side.t + b));
    out.equilibria.push_back({root.t, rises, root.energy, false});
  }
  if (rest + 1 == points.size()) out.equilibria.push_back({options.rest_t, true, points[rest].energy, true});

  // Bistable: the barrier to the nearest other minimum, both ways.
  if (out.bistable()) {
    const auto at_rest = std::find_if(out.equilibria.begin(), out.equilibria.end(), [](const Equilibrium& e) { return e.rest; });
    std::optional<std::pair<double, double>> best;  // (distance in t, barrier)
    for (auto it = out.equilibria.begin(); it != out.equilibria.end(); ++it) {
      if (!it->minimum || it->rest) continue;
      const auto from = std::min(it, at_rest), to = std::max(it, at_rest);
      double peak = -std::numeric_limits<double>::infinity();
      for (auto e = from; e != to; ++e) {
        if (!e->minimum) peak = std::max(peak, e->energy);
      }
      const double distance = std::abs(it->t - options.rest_t);
      if (std::isfinite(peak) && (!best || distance < best->first)) {
        best = {distance, peak};
        out.barrier = peak - at_rest->energy;
        out.reverse_barrier = peak - it->energy;
      }
    }
  }
  return out;
}

nlohmann::json EnergyLandscape::to_json() const {
  nlohmann::json samples_json = nlohmann::json::array();
  for (const EnergySample& s : samples) {
    samples_json.push_back({{"t", s.t},
                            {"E", s.energy},
                            {"dE_dt", optional_json(s.rate)},
                            {"length", {optional_json(s.length[0]), optional_json(s.length[1]), optional_json(s.length[2])}},
                            {"force", {optional_json(s.force[0]), optional_json(s.force[1]), optional_json(s.force[2])}}});
  }
  nlohmann::json eq = nlohmann::json::array();
  for (const Equilibrium& e : equilibria) {
    eq.push_back({{"t", e.t}, {"kind", e.minimum ? "minimum" : "maximum"}, {"E", e.energy}, {"rest", e.rest}});
  }
  nlohmann::json axes_json = nlohmann::json::array();
  for (const Vec3& d : axes) axes_json.push_back({d.x(), d.y(), d.z()});
  return {{"rest_t", rest_t},
          {"t_lambda", t_lambda},
          {"t_mu", t_mu},
          {"folds", folds},
          {"largest_E", largest_energy},
          {"bistable", bistable()},
          {"barrier", optional_json(barrier)},
          {"reverse_barrier", optional_json(reverse_barrier)},
          {"axes", axes_json},
          {"energy", samples_json},
          {"equilibria", eq}};
}

std::string EnergyLandscape::to_csv() const {
  // The samples and the equilibria (dE/dt = 0 there; no lengths computed), in increasing t.
  std::vector<std::pair<double, std::string>> rows;
  for (const EnergySample& s : samples) {
    const bool rest = s.t == rest_t;
    std::string row = format_number(s.t) + "," + format_number(s.energy) + "," + csv_number(s.rate);
    for (int k = 0; k < 3; ++k) row += "," + csv_number(s.length[k]);
    for (int k = 0; k < 3; ++k) row += "," + csv_number(s.force[k]);
    rows.push_back({s.t, row + (rest ? ",rest minimum" : ",") + "\n"});
  }
  for (const Equilibrium& e : equilibria) {
    if (e.rest) continue;
    rows.push_back({e.t, format_number(e.t) + "," + format_number(e.energy) + ",0,,,,,,," +
                             (e.minimum ? "minimum" : "maximum") + "\n"});
  }
  std::stable_sort(rows.begin(), rows.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::string out = "t,E,dE_dt,L1,L2,L3,force_1,force_2,force_3,equilibrium\n";
  for (const auto& row : rows) out += row.second;
  return out;
}

}  // namespace phedra
