#include "phedra/repair.h"

#include "phedra/errors.h"
#include "phedra/panel_nets.h"
#include "phedra/self_intersection.h"

#include <nlopt.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <cstdio>
#include <cstdlib>
#include <random>

namespace phedra {
namespace {

using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The required part of the interval: from t* this fraction of the way to each limit.
std::pair<double, double> required_range(const Assembly& a, double fraction) {
  const double t = a.t_star();
  const FlexionInterval& f = a.flexion_interval();
  if (fraction >= 1.0) return {f.lower.t, f.upper.t};
  return {t - fraction * (t - f.lower.t), t + fraction * (f.upper.t - t)};
}

/// How the panel shapes enter the constraints.
enum class ShapeMode {
  /// Every edge of the general net at least `edge_target` of the model size long
  /// and pointing the way its axial edge does, and every axial face simple: then
  /// every panel has its axial face's shape (MATH.md section 9). Stricter than
  /// needed, but the edge lengths move continuously where the panel margins have
  /// local minima (a sign change of an edge scale walks from row to row).
  positive_net,
  /// Every panel's shape margin at least `shape_target` (the exact rule).
  exact,
};

constexpr std::size_t slots_per_face = 5;

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

/// The optimizer's view of a design: its constraint values (<= 0 satisfied).
class Problem {
 public:
  Problem(const DesignVariables& variables, const RepairOptions& options, std::size_t panels, double size)
      : variables_(variables), options_(options), panels_(panels), size_(size) {}

  void set_mode(ShapeMode shapes, bool motion, double fraction) {
    shapes_ = shapes;
    motion_ = motion;
    fraction_ = fraction;
    cached_.clear();
  }
  std::size_t constraints() const { return slots_per_face * panels_ + 2; }
  std::size_t evaluations() const { return evaluations_; }

  /// Constraint values at x: per member face its shape values (ShapeMode), then
  /// the deepest penetration (x 10 over the model size) and the furthest hinge
  /// past shut (radians) over the required motion (0 without the motion).
  const std::vector<double>& at(const double* x) {
    if (!cached_.empty() && std::equal(cached_x_.begin(), cached_x_.end(), x)) return cached_;
    cached_x_.assign(x, x + variables_.size());
    cached_.assign(constraints(), 1.0);  // a design that does not build violates everything
    ++evaluations_;
    try {
      const Design d = design_from_json(variables_.preset_at(cached_x_));
      const Assembly& a = d.assembly;
      std::size_t k = 0;
      for (std::size_t m = 0; m < a.member_count(); ++m) {
        for (std::size_t f = 0; f < a.topology(m).face_count() && k < panels_; ++f, ++k) {
          const PanelNets nets = panel_nets(a, m, f);
          double* slot = &cached_[slots_per_face * k];
          if (shapes_ == ShapeMode::exact) {
            slot[0] = options_.shape_target - std::clamp(shape_margin(nets), -1.0, 1.0);
            std::fill(slot + 1, slot + slots_per_face, 0.0);
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
      cached_[motion] = cached_[motion + 1] = 0.0;
      if (motion_) {
        const auto [from, to] = required_range(a, fraction_);
        const MotionMargins m = motion_margins(d, from, to, options_.motion_samples);
        cached_[motion] = 10.0 * m.depth / size_;
        cached_[motion + 1] = m.folded + 1e-6;  // a hinge must stay open inside the range
      }
    } catch (const Error&) {
    }
    return cached_;
  }

 private:
  const DesignVariables& variables_;
  const RepairOptions& options_;
  std::size_t panels_;
  double size_;
  ShapeMode shapes_ = ShapeMode::exact;
  bool motion_ = false;
  double fraction_ = 1.0;
  std::size_t evaluations_ = 0;
  std::vector<double> cached_x_, cached_;
};

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

double total_violation(Problem& problem, const std::vector<double>& x) {
  double sum = 0.0;
  for (double v : problem.at(x.data())) sum += v > 0.0 ? v : 0.0;
  return sum;
}

/// Bounds, steps and stopping rules shared by the local searches.
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

/// Feasibility: minimise the summed violations with Subplex (Nelder-Mead on
/// subspaces: robust where the margins have kinks), stopping where they vanish.
/// Returns the feasible point, or where the search ended.
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

/// The feasible point nearest `target` on the segment from `feasible` (found by
/// bisection: the feasible part of the segment is taken as one piece).
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

/// One local search from the feasible x; returns the nearest feasible design it saw.
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

/// The buildability the result is judged by: the report itself, 200 samples a side.
BuildabilityReport verify(const json& preset, bool sweep = true) {
  BuildabilityOptions options;
  options.sweep_motion = sweep;
  options.diagnosis.hints = false;
  options.sweep.samples_per_side = 200;
  return assess_buildability(design_from_json(preset), nullptr, options);
}

std::string pointer_field(const json::json_pointer& pointer) {
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

/// Every number that differs between two presets, as fields (directions as turns).
std::vector<FieldChange> changes_between(const json& before, const json& after, double size,
                                         const json::json_pointer& at = json::json_pointer()) {
  std::vector<FieldChange> out;
  const json& b = before.at(at);
  const json& a = after.at(at);
  if (at.to_string().rfind("/directions/", 0) == 0 && b.is_array() && b.size() == 3) {
    if (b == a) return out;
    const auto u = b.get<std::vector<double>>(), v = a.get<std::vector<double>>();
    const double dot = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    const double cross = std::sqrt(std::pow(u[1] * v[2] - u[2] * v[1], 2) + std::pow(u[2] * v[0] - u[0] * v[2], 2) +
                                   std::pow(u[0] * v[1] - u[1] * v[0], 2));
    const double turn = std::atan2(cross, dot);
    out.push_back({pointer_field(at), b, a, turn * 180.0 / std::numbers::pi, turn});
    return out;
  }
  if (b.is_number() && a.is_number()) {
    if (b != a) out.push_back({pointer_field(at), b, a, a.get<double>() - b.get<double>(), std::abs(a.get<double>() - b.get<double>()) / size});
    return out;
  }
  if (b.is_array() && a.is_array() && a.size() == b.size()) {
    for (std::size_t k = 0; k < b.size(); ++k) {
      const auto more = changes_between(before, after, size, at / k);
      out.insert(out.end(), more.begin(), more.end());
    }
  } else if (b.is_object() && a.is_object()) {
    for (const auto& [key, value] : b.items()) {
      if (!a.contains(key)) continue;
      const auto more = changes_between(before, after, size, at / key);
      out.insert(out.end(), more.begin(), more.end());
    }
  }
  return out;
}

/// Every panel a simple quad (MATH.md section 9).
bool all_panels_simple(const Design& design) {
  const Assembly& a = design.assembly;
  for (std::size_t m = 0; m < a.member_count(); ++m) {
    for (std::size_t f = 0; f < a.topology(m).face_count(); ++f) {
      if (!(shape_margin(panel_nets(a, m, f)) > 0.0)) return false;
    }
  }
  return true;
}

/// The variables' displacement when the held apex height's neighbours at
/// `offsets` (in its own list of heights) move by `change`, the others stay
/// (empty when the held field is no apex height or has no such neighbour).
std::vector<double> neighbour_line(const DesignVariables& variables, const std::vector<int>& offsets, double change) {
  const std::vector<DesignVariable>& v = variables.variables();
  // "apex_heights[3]" / "tube.apex_heights[3]" -> ("apex_heights", 3)
  auto split = [](const std::string& field, std::string& list, long& index) {
    const std::size_t open = field.rfind('[');
    if (open == std::string::npos || field.back() != ']' || field.find("apex_heights") == std::string::npos) return false;
    list = field.substr(0, open);
    index = std::stol(field.substr(open + 1, field.size() - open - 2));
    return field.find('[') == open;  // one index: a height, not a point's coordinate
  };
  std::string held_list;
  long held = -1;
  for (const DesignVariable& d : v) {
    if (d.fixed && split(d.field, held_list, held)) break;
    held = -1;
  }
  if (held < 0) return {};
  std::vector<double> out(v.size(), 0.0);
  bool any = false;
  for (std::size_t k = 0; k < v.size(); ++k) {
    std::string list;
    long index = 0;
    if (v[k].fixed || !split(v[k].field, list, index) || list != held_list) continue;
    if (std::find(offsets.begin(), offsets.end(), static_cast<int>(index - held)) == offsets.end()) continue;
    out[k] = change;
    any = true;
  }
  return any ? out : std::vector<double>{};
}

/// The trajectory variables' displacement that puts the points within
/// `window` of the held point `held` where a soft selection of the drag puts
/// them: at their place when the drag began plus 1 - |offset| / (window + 1)
/// of the held point's move since (`origin`: the trajectory then; `now`: the
/// held point now). Empty when there is no such variable.
std::vector<double> trajectory_line(const DesignVariables& fields, long held, int window, const json& origin,
                                    const json& now) {
  const std::vector<DesignVariable>& v = fields.variables();
  std::vector<double> out(v.size(), 0.0);
  bool any = false;
  for (std::size_t k = 0; k < v.size(); ++k) {
    long point = 0;
    int c = 0;
    if (v[k].fixed || std::sscanf(v[k].field.c_str(), "trajectory[%ld][%d]", &point, &c) != 2) continue;
    const long offset = std::labs(point - held);
    if (offset == 0 || offset > window || c < 0 || c > 2 || point >= static_cast<long>(origin.size())) continue;
    const double follow = 1.0 - static_cast<double>(offset) / (window + 1.0);
    const double moved = now[c].get<double>() - origin[held][c].get<double>();
    out[k] = origin[point][c].get<double>() + follow * moved - v[k].start;
    any = true;
  }
  return any ? out : std::vector<double>{};
}

}  // namespace

bool buildable_at_t_star(const Design& design) {
  return all_panels_simple(design) && !self_intersection_at_t_star(design);
}

std::optional<Projection> project_buildable(const json& preset, const ProjectionOptions& options) {
  const Clock::time_point start = Clock::now();
  Projection out;
  const Design input = design_from_json(preset);
  ++out.evaluations;
  const bool simple = all_panels_simple(input);  // (the collision check at t* costs far more: only then)
  if (simple && !self_intersection_at_t_star(input)) {
    out.preset = preset;
    out.how = "already";
    return out;
  }
  RepairOptions search;
  search.vary = options.vary;
  search.fixed = options.fixed;
  search.max_seconds = options.max_seconds;
  std::optional<DesignVariables> variables;
  try {
    variables.emplace(preset, options.vary, input.assembly.model_size(), options.fixed);
  } catch (const InvalidInputError&) {
    return std::nullopt;  // nothing to vary
  }
  std::size_t panels = 0;
  for (std::size_t m = 0; m < input.assembly.member_count(); ++m) panels += input.assembly.topology(m).face_count();
  const std::vector<double> x0 = variables->start();
  auto left = [&] { return options.max_seconds - seconds_since(start); };
  // Lines whose far end may be buildable: the drag's last displacement, then
  // the held height's neighbours following it (in the varied fields); for a
  // held trajectory point, its neighbours following it with a tent falloff over
  // windows of 1, 2, 4, ... points a side (on a dense trajectory a point moved
  // by one segment's length reverses a segment at once).
  struct Line {
    std::string how;
    const DesignVariables* fields;
    std::vector<double> d;
    int window = -1;  ///< trajectory lines: the index of the window
  };
  std::vector<Line> lines;
  if (options.continue_along.size() == variables->size()) lines.push_back({"continued", &*variables, options.continue_along});
  if (options.held_change != 0.0) {
    for (const std::vector<int>& offsets : std::vector<std::vector<int>>{{-1}, {1}, {-1, 1}, {-2, -1, 1, 2}}) {
      std::vector<double> d = neighbour_line(*variables, offsets, options.held_change);
      if (!d.empty()) lines.push_back({"neighbours", &*variables, std::move(d)});
    }
  }
  std::optional<DesignVariables> path;
  const json* origin = options.drag_origin.is_object() ? &options.drag_origin : nullptr;
  if (origin && origin->contains("trajectory") && (*origin)["trajectory"].is_array() && preset.contains("trajectory") &&
      preset["trajectory"].is_array() && (*origin)["trajectory"].size() == preset["trajectory"].size() &&
      !options.fixed.empty() && options.fixed[0].rfind("/trajectory/", 0) == 0) {
    try {
      path.emplace(preset, std::vector<VariableGroup>{VariableGroup::trajectory}, input.assembly.model_size(), options.fixed);
    } catch (const InvalidInputError&) {
    }
  }
  if (path) {
    const long held = std::stol(options.fixed[0].substr(std::string("/trajectory/").size()));
    const int windows[] = {1, 2, 4, 8, 16, 32};
    const int count = static_cast<int>(std::size(windows));
    for (int k = 0; k < count; ++k) {
      const int w = (options.first_window + k) % count;
      std::vector<double> d =
          trajectory_line(*path, held, windows[w], (*origin)["trajectory"], preset["trajectory"][static_cast<std::size_t>(held)]);
      if (!d.empty()) lines.push_back({"trajectory", &*path, std::move(d), w});
    }
  }
  // Panel shapes along a line are cheap; the collision check at t* is done at
  // the point chosen on it only.
  auto design_at = [&](const Line& line, double lambda) -> std::optional<Design> {
    std::vector<double> x = line.fields->start();
    for (std::size_t k = 0; k < x.size(); ++k) x[k] += lambda * line.d[k];
    ++out.evaluations;
    try {
      return design_from_json(line.fields->preset_at(x));
    } catch (const Error&) {
      return std::nullopt;
    }
  };
  // The design at lambda on the line when its panels are all simple and it has
  // not grown much beyond the user's (a trajectory edge turned nearly into its
  // profile plane sends the axial net far out while every panel stays simple).
  // No larger than a quarter beyond what the held field's own move makes of the
  // design the drag began with (not compounding step after step); found once.
  double limit = 0.0;
  auto size_limit = [&] {
    if (limit > 0.0) return limit;
    limit = 1.5 * input.assembly.model_size();
    if (origin && options.origin_size > 0.0 && !options.fixed.empty()) {
      try {
        json own = *origin;
        own.at(json::json_pointer(options.fixed[0])) = preset.at(json::json_pointer(options.fixed[0]));
        ++out.evaluations;
        limit = 1.25 * std::max(options.origin_size, design_from_json(own).assembly.model_size());
      } catch (const Error&) {
        limit = 1.25 * options.origin_size;
      } catch (const json::exception&) {
      }
    }
    return limit;
  };
  auto simple_at = [&](const Line& line, double lambda) {
    std::optional<Design> design = design_at(line, lambda);
    if (design && (!all_panels_simple(*design) || !(design->assembly.model_size() <= size_limit()))) {
      design.reset();
    }
    return design;
  };
  for (const Line& line : lines) {
    if (left() <= 0.0) break;
    std::optional<Design> chosen = simple_at(line, 1.0);
    if (!chosen) continue;
    double good = 1.0, bad = 0.0;
    for (int step = 0; step < 2 && left() > 0.0; ++step) {
      const double middle = 0.5 * (good + bad);
      if (std::optional<Design> nearer = simple_at(line, middle)) {
        good = middle;
        chosen.emplace(std::move(*nearer));
      } else {
        bad = middle;
      }
    }
    if (self_intersection_at_t_star(*chosen)) continue;
    std::vector<double> x = line.fields->start();
    for (std::size_t k = 0; k < x.size(); ++k) x[k] += good * line.d[k];
    if (line.fields == &*variables) {
      out.displacement.assign(x.size(), 0.0);
      for (std::size_t k = 0; k < x.size(); ++k) out.displacement[k] = good * line.d[k];
    }
    out.preset = line.fields->preset_at(x);
    out.moved = true;
    out.how = line.how;
    out.window = line.window;
    return out;
  }
  Problem problem(*variables, search, panels, input.assembly.model_size());
  problem.set_mode(ShapeMode::positive_net, false, 1.0);
  std::vector<double> x = feasible_search(*variables, problem, x0, search, left(), options.max_evaluations);
  problem.set_mode(ShapeMode::exact, false, 1.0);
  if (total_violation(problem, x) > 0.0 && left() > 0.0) {
    x = feasible_search(*variables, problem, x0, search, left(), options.max_evaluations);
  }
  out.evaluations += problem.evaluations();
  if (total_violation(problem, x) > 0.0) return std::nullopt;
  out.preset = variables->preset_at(x);
  out.moved = true;
  out.how = "search";
  out.displacement.assign(x.size(), 0.0);
  for (std::size_t k = 0; k < x.size(); ++k) out.displacement[k] = x[k] - x0[k];
  if (!buildable_at_t_star(design_from_json(out.preset))) return std::nullopt;
  return out;
}

std::optional<Projection> KeepBuildableDrag::step(const json& preset, const std::string& held, const json& previous,
                                                  ProjectionOptions options) {
  const json& now = preset.at(json::json_pointer(held));
  const double change = now.is_number() && previous.is_number() ? now.get<double>() - previous.get<double>() : 0.0;
  options.fixed = {held};
  options.held_change = change;
  if (held != held_) {  // a new drag: where its soft selection starts from, and its size
    origin_ = preset;
    origin_.at(json::json_pointer(held)) = previous;
    window_ = 0;
    try {
      origin_size_ = design_from_json(origin_).assembly.model_size();
    } catch (const Error&) {
      origin_size_ = 0.0;
    }
  }
  options.drag_origin = origin_;
  options.origin_size = origin_size_;
  options.first_window = window_;
  options.continue_along.clear();
  if (held == held_ && !displacement_.empty()) {
    const double ratio = change != 0.0 && change_ != 0.0 ? change / change_ : 1.0;
    for (double d : displacement_) options.continue_along.push_back(ratio * d);
  }
  held_ = held;
  change_ = change;
  displacement_.clear();
  std::optional<Projection> p = project_buildable(preset, options);
  if (p && p->moved) displacement_ = p->displacement;
  if (p && p->window >= 0) window_ = p->window;
  return p;
}

json named_result(const json& result, const std::string& input_name, const std::string& vary, const RepairResult& r) {
  json out = result;
  if (r.found) {
    out["name"] = input_name + "-repaired";
    out["description"] = "Repaired by phedra repair from \"" + input_name + "\" (varied: " + vary + "): " +
                         r.after.summary() + ".";
  } else {
    out["name"] = input_name + "-closest";
    out["description"] = "The closest design phedra repair found to a buildable one from \"" + input_name +
                         "\" (varied: " + vary + "); not buildable: " + r.after.summary() + ".";
  }
  return out;
}

double buildable_fraction(const BuildabilityReport& r) {
  const auto range = r.interval();
  if (!range || !r.swept) return 0.0;
  const double below = r.t_star - r.t_lambda, above = r.t_mu - r.t_star;
  const double low = below > 0.0 ? (r.t_star - range->first) / below : 1.0;
  const double high = above > 0.0 ? (range->second - r.t_star) / above : 1.0;
  return std::clamp(std::min(low, high), 0.0, 1.0);
}

RepairResult repair(const json& preset, const RepairOptions& options) {
  if (!(options.required_fraction >= 0.0 && options.required_fraction <= 1.0)) {
    throw InvalidInputError("--require", "the buildable part must be a fraction in [0, 1]");
  }
  const Clock::time_point start = Clock::now();
  RepairResult r;
  const Design input = design_from_json(preset);
  const double size = input.assembly.model_size();
  const DesignVariables variables(preset, options.vary, size, options.fixed);  // bad --vary: an error even when nothing is to do
  r.notes = variables.notes();
  r.before = verify(preset);
  const double required = options.required_fraction;
  auto meets = [&](const BuildabilityReport& b, double fraction) {
    return b.panels_simple() && b.interval() && buildable_fraction(b) >= fraction - 1e-12;
  };
  if (meets(r.before, required)) {
    r.found = r.already_buildable = true;
    r.fraction = buildable_fraction(r.before);
    r.preset = preset;
    r.after = r.before;
    r.seconds = seconds_since(start);
    return r;
  }
  if (!r.before.self_crossing_members.empty()) {
    // No numbers make it buildable: its closed linkage is a crossed four-bar.
    const bool several = r.before.self_crossing_members.size() > 1;
    r.closest = std::string(several ? "its anti-parallelogram tubes cross themselves" : "its anti-parallelogram tube crosses itself") +
                " by kind (the closed linkage L0 is a crossed four-bar, MATH.md section 6): no change of "
                "heights, directions or trajectory makes that buildable; a parallelogram tube (all '+') can be";
    r.after = r.before;
    r.seconds = seconds_since(start);
    return r;
  }
  std::size_t panels = 0;
  for (std::size_t m = 0; m < input.assembly.member_count(); ++m) panels += input.assembly.topology(m).face_count();
  Problem problem(variables, options, panels, size);
  std::mt19937_64 rng(options.seed);
  std::normal_distribution<double> normal;

  struct Candidate {
    std::vector<double> x;
    double distance = std::numeric_limits<double>::infinity();
    double fraction = -1.0;
    BuildabilityReport report;
  };
  std::optional<Candidate> best;         // meets the requirement, nearest
  std::optional<Candidate> best_partial; // simple panels, widest part
  std::optional<Candidate> closest;      // the least bad, for the report

  auto consider = [&](const std::vector<double>& x, double fraction_wanted) {
    Candidate c;
    c.x = x;
    c.distance = variables.distance(x);
    try {
      c.report = verify(variables.preset_at(x));
    } catch (const Error&) {
      return false;
    }
    c.fraction = c.report.panels_simple() ? buildable_fraction(c.report) : -1.0;
    if (!closest || c.report.invalid.size() < closest->report.invalid.size() ||
        (c.report.invalid.size() == closest->report.invalid.size() && c.fraction > closest->fraction)) {
      closest = c;
    }
    if (meets(c.report, fraction_wanted)) {
      if (!best || c.distance < best->distance) best = c;
      return true;
    }
    if (c.fraction >= 0.0 && (!best_partial || c.fraction > best_partial->fraction ||
                              (c.fraction == best_partial->fraction && c.distance < best_partial->distance))) {
      best_partial = c;
    }
    return false;
  };
  auto time_left = [&] { return options.max_seconds - seconds_since(start); };
  const std::vector<double> x0 = variables.start();
  consider(x0, required);  // the input itself: the widest part to beat

  // Stage 1, panel shapes alone (cheap: no motion): from the input and from
  // perturbed starts (the simple designs need not form one connected set), a
  // design with every panel simple (the positive net first, the exact rule when
  // that fails), moved towards the input (bisection) and to the nearest one.
  std::optional<Candidate> closest_shapes;  // the fewest panels not simple, when no start succeeds
  auto simple_from = [&](const std::vector<double>& from) -> std::optional<std::vector<double>> {
    ++r.starts;
    std::vector<double> x = from;
    problem.set_mode(ShapeMode::exact, false, required);
    if (total_violation(problem, x) > 0.0) {
      problem.set_mode(ShapeMode::positive_net, false, required);
      x = feasible_search(variables, problem, x, options, time_left(), options.max_evaluations);
      problem.set_mode(ShapeMode::exact, false, required);
      if (total_violation(problem, x) > 0.0) x = feasible_search(variables, problem, from, options, time_left(), options.max_evaluations);
      if (total_violation(problem, x) > 0.0) {
        try {
          Candidate c{x, variables.distance(x), -1.0, verify(variables.preset_at(x), false)};
          if (!closest_shapes || c.report.invalid.size() < closest_shapes->report.invalid.size()) closest_shapes = c;
        } catch (const Error&) {
        }
        return std::nullopt;
      }
      x = towards(problem, x, x0);
      x = local_search(variables, problem, x, options, time_left(), options.max_evaluations);
    }
    return x;
  };
  // Stage 2, the motion: from a simple design, no collision over the required
  // part, then towards the input and to the nearest such design.
  auto motion_from = [&](std::vector<double> x, double fraction) {
    problem.set_mode(ShapeMode::exact, true, fraction);
    // Already free over the required part: the nearest simple design is the nearest buildable one.
    if (total_violation(problem, x) == 0.0) return consider(x, fraction);
    x = feasible_search(variables, problem, x, options, time_left(), options.motion_evaluations);
    if (total_violation(problem, x) == 0.0) {
      x = towards(problem, x, x0);
      x = local_search(variables, problem, x, options, time_left(), options.motion_evaluations);
    }
    return consider(x, fraction);
  };
  // Each simple design found (the input's own first) goes to stage 2 at once;
  // further starts only while none of them gave a buildable design.
  std::vector<std::vector<double>> simple;
  const double shape_time = 0.5 * options.max_seconds;
  for (std::size_t s = 0; s <= options.restarts && seconds_since(start) < shape_time; ++s) {
    std::vector<double> x = x0;
    const double radius = std::min(0.4, 0.03 * static_cast<double>(s));
    for (std::size_t k = 0; k < x.size(); ++k) {
      if (!variables.variables()[k].fixed) x[k] += radius * variables.variables()[k].scale * normal(rng);
    }
    if (std::optional<std::vector<double>> found = simple_from(x)) {
      simple.push_back(std::move(*found));
      if (time_left() > 0.0 && motion_from(simple.back(), required)) break;
      if (simple.size() >= options.shape_candidates) break;
    }
  }
  if (!best && options.widest_fallback && !simple.empty()) {
    for (const double fraction : {0.75, 0.5, 0.25, 0.0}) {
      if (fraction >= required || time_left() <= 0.0) continue;
      if (motion_from(best_partial ? best_partial->x : simple.front(), fraction)) break;
    }
  }
  if (!best && options.widest_fallback && best_partial && best_partial->fraction > 0.0) best = best_partial;
  if (best) {
    // Changes below 0.1 % of the model size (or 0.06 degrees) are mostly the
    // search's noise: put them back while the design stays as buildable without
    // them (all of them, else the turns or the lengths alone, else smaller ones).
    for (const double threshold : {1e-3, 1e-4}) {
      for (const int only : {-1, static_cast<int>(DesignVariable::Kind::turn), static_cast<int>(DesignVariable::Kind::length)}) {
        std::vector<double> tidy = best->x;
        bool any = false;
        for (std::size_t k = 0; k < tidy.size(); ++k) {
          const DesignVariable& v = variables.variables()[k];
          if (only >= 0 && static_cast<int>(v.kind) != only) continue;
          if (tidy[k] != v.start && std::abs(tidy[k] - v.start) < threshold * v.scale) {
            tidy[k] = v.start;
            any = true;
          }
        }
        if (!any) continue;
        try {
          const BuildabilityReport report = verify(variables.preset_at(tidy));
          if (report.panels_simple() && buildable_fraction(report) >= best->fraction - 1e-12) {
            best->x = tidy;
            best->distance = variables.distance(tidy);
            best->report = report;
          }
        } catch (const Error&) {
        }
      }
    }
  }
  if (best) {
    r.found = true;
    r.fraction = buildable_fraction(best->report);
  }
  if (!best && closest && !closest->report.panels_simple() && closest_shapes &&
      closest_shapes->report.invalid.size() < closest->report.invalid.size()) {
    closest = closest_shapes;
  }
  r.evaluations = problem.evaluations();
  if (r.found) {
    r.preset = variables.preset_at(best->x);
    r.after = best->report;
    r.distance = best->distance;
    r.changes = changes_between(preset, r.preset, size);
  } else {
    r.after = closest ? closest->report : r.before;
    r.closest_preset = variables.preset_at(closest ? closest->x : x0);
    const BuildabilityReport& c = r.after;
    if (!c.panels_simple()) {
      r.closest = "no design near the input has every panel simple: at best " + std::to_string(c.invalid.size()) +
                  " stay not simple (panels " + c.invalid_list() + ")";
    } else if (c.motion.at_t_star) {
      r.closest = "every panel can be made simple, but the configuration at t* then collides: " +
                  describe(*c.motion.at_t_star, c.members > 1);
    } else {
      r.closest = "the best design found is buildable over " + std::to_string(static_cast<int>(100.0 * buildable_fraction(c))) +
                  " % of the way from t* to the limits only";
    }
  }
  r.seconds = seconds_since(start);
  return r;
}

}  // namespace phedra
