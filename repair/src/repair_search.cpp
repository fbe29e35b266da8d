#include "repair_search.h"

#include "phedra/design_preset.h"
#include "phedra/errors.h"
#include "phedra/panel_nets.h"
#include "phedra/panel_size.h"
#include "phedra/self_intersection.h"

#include <nlopt.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace phedra::repair_search {

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double t_star_margin(const Assembly& a) {
  const double t = a.t_star();
  const FlexionInterval& f = a.flexion_interval();
  const double length = f.upper.t - f.lower.t;
  return length > 0.0 ? std::min(t - f.lower.t, f.upper.t - t) / length : 0.0;
}

std::pair<double, double> required_range(const Assembly& a, double fraction) {
  const double t = a.t_star();
  const FlexionInterval& f = a.flexion_interval();
  if (fraction >= 1.0) return {f.lower.t, f.upper.t};
  return {t - fraction * (t - f.lower.t), t + fraction * (f.upper.t - t)};
}

namespace {


/// The positive-net constraint values of one face (<= 0 satisfied).
std::array<double, slots_per_face> positive_net_values(const PanelNets& p, double size, double edge_target,
                                                       double shape_target) {
  std::array<double, slots_per_face> out{};
  if (p.boundary) {
    out[0] = shape_target - std::clamp(shape_margin(p), -1.0, 1.0);
    return out;
  }
  for (int k = 0; k < 4; ++k) {
    const Vec3 axial = p.axial[(k + 1) % 4] - p.axial[k];
    const double length = axial.norm();
    const double along = length > 0.0 ? (p.general[(k + 1) % 4] - p.general[k]).dot(axial) / length : 0.0;
    out[k] = std::min(edge_target - along / size, 1.0);
  }
  const PanelNets axial_only{p.axial, p.axial, false, p.row, p.column, p.net_columns};
  out[4] = shape_target - std::clamp(shape_margin(axial_only), -1.0, 1.0);
  return out;
}

}  // namespace

const std::vector<double>& Problem::at(const double* x) {
  if (!cached_.empty() && std::equal(cached_x_.begin(), cached_x_.end(), x)) return cached_;
  cached_x_.assign(x, x + variables_.size());
  cached_.assign(constraints(), 1.0);  // a design that does not build violates everything
  ++evaluations_;
  try {
    const Design d = design_from_json(variables_.preset_at(cached_x_));
    const Assembly& a = d.assembly;
    std::vector<PanelNets> faces;
    for (std::size_t m = 0; m < a.member_count(); ++m) {
      for (std::size_t f = 0; f < a.topology(m).face_count() && faces.size() < panels_; ++f) faces.push_back(panel_nets(a, m, f));
    }
    // The size bounds (panel_size.h) as margins: the log of the longest edge over
    // its bound, of the aspect's bound over the aspect (<= 0 within them).
    std::vector<double> longest(faces.size());
    for (std::size_t k = 0; k < faces.size(); ++k) longest[k] = std::sqrt(longest_edge_squared(faces[k].general));
    std::vector<double> sorted = longest;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double median = sorted.empty() ? 0.0 : sorted[sorted.size() / 2];
    const SizeBounds& bounds = options_.bounds;
    std::size_t k = 0;
    for (; k < faces.size(); ++k) {
      {
        const PanelNets& nets = faces[k];
        double* slot = &cached_[slots_per_face * k];
        if (shapes_ == ShapeMode::exact) {
          slot[0] = options_.shape_target - std::clamp(shape_margin(nets), -1.0, 1.0);
          std::fill(slot + 1, slot + slots_per_face, 0.0);
          if (bounds.max_edge_ratio > 0.0 && median > 0.0) {
            slot[1] = std::clamp(std::log(longest[k] / (bounds.max_edge_ratio * median)), -1.0, 1.0);
          }
          const double aspect = longest[k] > 0.0 ? quad_area(nets.general) / (longest[k] * longest[k]) : 0.0;
          if (bounds.min_aspect > 0.0) slot[2] = aspect > 0.0 ? std::clamp(std::log(bounds.min_aspect / aspect), -1.0, 1.0) : 1.0;
        } else {
          const auto values = positive_net_values(nets, size_, options_.edge_target, options_.shape_target);
          std::copy(values.begin(), values.end(), slot);
        }
      }
    }
    if (k != panels_) {
      std::fill(cached_.begin(), cached_.end(), 1.0);  // another topology (a curve's segment count changed)
      return cached_;
    }
    const std::size_t motion = slots_per_face * panels_;
    cached_[motion] = cached_[motion + 1] = cached_[motion + 2] = cached_[motion + 3] = 0.0;
    // t* at a flexion limit is a design with two coinciding profile planes: its
    // positions are ill-conditioned there (phedra check's reproduction fails)
    // and the near side of the interval is empty, so "buildable over all of it"
    // would be vacuous. Kept away from the limits in the motion modes.
    if (motion_ != MotionMode::none && margin_target_ > 0.0) {
      cached_[motion + 3] = std::clamp((margin_target_ - t_star_margin(a)) / margin_target_, -1.0, 1.0);
    }
    if (motion_ == MotionMode::t_star) {
      const MotionMargins m = motion_margins(d, a.t_star(), a.t_star(), 0);
      cached_[motion] = 10.0 * m.depth_sum / size_;
      // At t* alone the openings are not continued from anywhere: they lie in
      // [0, 2 pi), and a hinge within 1e-6 of shut (0 or 2 pi) is one that a
      // collision test calls folded there; the margin is minus that distance.
      cached_[motion + 1] = std::max(m.folded + 1e-6, 0.0);
    } else if (motion_ == MotionMode::range) {
      const auto [from, to] = required_range(a, fraction_);
      const MotionMargins m = motion_margins(d, from, to, options_.motion_samples);
      cached_[motion] = 10.0 * m.depth_sum / size_;
      cached_[motion + 1] = m.folded + 1e-6;  // a hinge must stay open inside the range
      if (bounds.max_growth > 0.0) cached_[motion + 2] = std::min(std::log(m.growth / bounds.max_growth), 1.0);
    }
  } catch (const Error&) {
  }
  return cached_;
}

namespace {

struct Search {
  const DesignVariables& variables;
  Problem& problem;
};

double objective(unsigned n, const double* x, double* gradient, void* data) {
  const Search& s = *static_cast<const Search*>(data);
  double sum = 0.0;
  for (unsigned k = 0; k < n; ++k) {
    const DesignVariable& v = s.variables.variables()[k];
    const double d = (x[k] - v.start) / v.scale;
    sum += d * d;
    if (gradient) gradient[k] = 2.0 * d / v.scale;
  }
  return sum;
}

/// The summed violations (an exact penalty: it reaches zero, where squares only
/// approach it), what the feasibility phase drives to zero; the first point
/// where they vanish ends the search (nlopt::forced_stop).
struct Feasibility {
  Search search;
  std::vector<double> found;
};

double violation(unsigned n, const double* x, double* gradient, void* data) {
  Feasibility& f = *static_cast<Feasibility*>(data);
  const std::vector<double>& c = f.search.problem.at(x);
  double sum = 0.0;
  for (double v : c) sum += v > 0.0 ? v : 0.0;
  (void)gradient;
  if (sum == 0.0) {
    f.found.assign(x, x + n);
    throw nlopt::forced_stop();
  }
  return sum;
}

/// The nearest point: Subplex on distance^2 + weight * summed violations (an
/// exact penalty: for a large enough weight its minimum is the constrained one,
/// and Subplex copes with its kinks), keeping the nearest feasible design seen.
struct Nearest {
  Search search;
  double weight = 100.0;
  std::vector<double> best;
  double best_distance = std::numeric_limits<double>::infinity();
};

double penalized(unsigned n, const double* x, double* gradient, void* data) {
  Nearest& s = *static_cast<Nearest*>(data);
  const double distance = objective(n, x, gradient, &s.search);
  double sum = 0.0;
  for (double v : s.search.problem.at(x)) sum += v > 0.0 ? v : 0.0;
  if (sum == 0.0 && distance < s.best_distance) {
    s.best_distance = distance;
    s.best.assign(x, x + n);
  }
  return distance + s.weight * sum;
}

}  // namespace

void configure(nlopt::opt& opt, const DesignVariables& variables, std::vector<double>& x, const RepairOptions& options,
               double seconds_left) {
  const std::size_t n = variables.size();
  std::vector<double> step(n), lower(n), upper(n), tolerance(n);
  for (std::size_t k = 0; k < n; ++k) {
    const DesignVariable& v = variables.variables()[k];
    step[k] = 0.02 * v.scale;
    const double reach = v.fixed ? 0.0 : v.kind == DesignVariable::Kind::turn ? 0.5 * std::numbers::pi : 0.5 * v.scale;
    lower[k] = v.start - reach;
    upper[k] = v.start + reach;
    x[k] = std::clamp(x[k], lower[k], upper[k]);
    tolerance[k] = 1e-7 * v.scale;
  }
  opt.set_lower_bounds(lower);
  opt.set_upper_bounds(upper);
  opt.set_initial_step(step);
  opt.set_xtol_abs(tolerance);
  opt.set_maxeval(static_cast<int>(options.max_evaluations));
  opt.set_maxtime(std::max(1e-3, seconds_left));
}

void run_opt(nlopt::opt& opt, std::vector<double>& x) {
  double value = 0.0;
  try {
    opt.optimize(x, value);
  } catch (const nlopt::roundoff_limited&) {
  } catch (const nlopt::forced_stop&) {
  } catch (const std::runtime_error&) {  // NLopt's generic failure: keep where it stopped
  }
}

double total_violation(Problem& problem, const std::vector<double>& x) {
  double sum = 0.0;
  for (double v : problem.at(x.data())) sum += v > 0.0 ? v : 0.0;
  return sum;
}

std::vector<double> feasible_search(const DesignVariables& variables, Problem& problem, std::vector<double> x,
                                    const RepairOptions& options, double seconds_left, std::size_t evaluations) {
  if (total_violation(problem, x) == 0.0) return x;
  nlopt::opt opt(nlopt::LN_SBPLX, static_cast<unsigned>(variables.size()));
  Feasibility feasibility{{variables, problem}, {}};
  opt.set_min_objective(violation, &feasibility);
  configure(opt, variables, x, options, seconds_left);
  opt.set_maxeval(static_cast<int>(evaluations));
  run_opt(opt, x);
  if (!feasibility.found.empty()) return feasibility.found;
  return x;
}

std::vector<double> towards(Problem& problem, const std::vector<double>& feasible, const std::vector<double>& target) {
  auto at = [&](double a) {
    std::vector<double> x(feasible.size());
    for (std::size_t k = 0; k < x.size(); ++k) x[k] = target[k] + a * (feasible[k] - target[k]);
    return x;
  };
  double infeasible = 0.0, ok = 1.0;
  for (int step = 0; step < 10; ++step) {
    const double middle = 0.5 * (infeasible + ok);
    (total_violation(problem, at(middle)) == 0.0 ? ok : infeasible) = middle;
  }
  return ok < 1.0 ? at(ok) : feasible;
}

std::vector<double> local_search(const DesignVariables& variables, Problem& problem, std::vector<double> x,
                                 const RepairOptions& options, double seconds_left, std::size_t evaluations) {
  nlopt::opt opt(nlopt::LN_SBPLX, static_cast<unsigned>(variables.size()));
  Nearest nearest{{variables, problem}, 100.0, {}, 0.0};
  nearest.best = x;
  nearest.best_distance = objective(static_cast<unsigned>(x.size()), x.data(), nullptr, &nearest.search);
  opt.set_min_objective(penalized, &nearest);
  configure(opt, variables, x, options, seconds_left);
  opt.set_ftol_abs(1e-6);
  opt.set_maxeval(static_cast<int>(evaluations));
  run_opt(opt, x);
  return nearest.best;
}

std::optional<std::vector<double>> scatter_search(const DesignVariables& variables, Problem& problem,
                                                  const std::vector<double>& center, std::size_t samples,
                                                  std::size_t polish, std::mt19937_64& rng, const RepairOptions& options,
                                                  double seconds_left) {
  const Clock::time_point start = Clock::now();
  std::normal_distribution<double> normal;
  const std::vector<DesignVariable>& v = variables.variables();
  std::optional<std::vector<double>> nearest;
  double nearest_distance = std::numeric_limits<double>::infinity();
  std::vector<std::pair<double, std::vector<double>>> least;  // (violation, x), the `polish` smallest
  for (std::size_t s = 0; s < samples && seconds_since(start) < seconds_left; ++s) {
    const double radius = 0.05 + 0.55 * static_cast<double>(s % 12) / 11.0;
    std::vector<double> x = center;
    for (std::size_t k = 0; k < x.size(); ++k) {
      if (v[k].fixed) continue;
      const double reach = v[k].kind == DesignVariable::Kind::turn ? 0.5 * std::numbers::pi : 0.5 * v[k].scale;
      x[k] = std::clamp(x[k] + radius * v[k].scale * normal(rng), v[k].start - reach, v[k].start + reach);
    }
    const double violation = total_violation(problem, x);
    if (violation == 0.0) {
      const double d = variables.distance(x);
      if (d < nearest_distance) {
        nearest_distance = d;
        nearest = x;
      }
    } else if (!nearest) {
      least.emplace_back(violation, std::move(x));
      std::sort(least.begin(), least.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      if (least.size() > polish) least.pop_back();
    }
  }
  if (nearest) return nearest;
  for (const auto& [violation, x] : least) {
    std::vector<double> found =
        feasible_search(variables, problem, x, options, seconds_left - seconds_since(start), options.max_evaluations);
    if (total_violation(problem, found) > 0.0) continue;
    const double d = variables.distance(found);
    if (d < nearest_distance) {
      nearest_distance = d;
      nearest = std::move(found);
    }
  }
  return nearest;
}

std::string pointer_field(const nlohmann::json::json_pointer& pointer) {
  // "/tube/apex_heights/3" -> "tube.apex_heights[3]"
  std::string out;
  const std::string text = pointer.to_string();
  std::size_t start = 1;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find('/', start), text.size());
    const std::string part = text.substr(start, end - start);
    const bool index = !part.empty() && part.find_first_not_of("0123456789") == std::string::npos;
    out += index ? "[" + part + "]" : (out.empty() ? part : "." + part);
    start = end + 1;
  }
  return out;
}

bool all_panels_simple(const Design& design, const SizeBounds& bounds) {
  const Assembly& a = design.assembly;
  std::vector<double> longest;
  std::vector<double> aspects;
  for (std::size_t m = 0; m < a.member_count(); ++m) {
    for (std::size_t f = 0; f < a.topology(m).face_count(); ++f) {
      const PanelNets nets = panel_nets(a, m, f);
      if (!(shape_margin(nets) > 0.0)) return false;
      const double e2 = longest_edge_squared(nets.general);
      longest.push_back(std::sqrt(e2));
      aspects.push_back(e2 > 0.0 ? quad_area(nets.general) / e2 : 0.0);
    }
  }
  if (bounds.min_aspect > 0.0 && std::any_of(aspects.begin(), aspects.end(), [&](double s) { return s < bounds.min_aspect; })) {
    return false;
  }
  if (bounds.max_edge_ratio > 0.0 && !longest.empty()) {
    std::vector<double> sorted = longest;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double limit = bounds.max_edge_ratio * sorted[sorted.size() / 2];
    if (std::any_of(longest.begin(), longest.end(), [&](double e) { return e > limit; })) return false;
  }
  return true;
}

}  // namespace phedra::repair_search
