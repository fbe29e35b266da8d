#include "phedra/keep_buildable.h"

#include "repair_search.h"

#include "phedra/design_preset.h"
#include "phedra/errors.h"
#include "phedra/self_intersection.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace phedra {
namespace {

using json = nlohmann::json;
using namespace repair_search;

/// The variables' displacement when the held apex height's neighbours at
/// `offsets` (in its own list of heights) move by `change`, the others stay
/// (empty when the held field, "apex_heights[3]", is no apex height or has no
/// such neighbour).
std::vector<double> neighbour_line(const DesignVariables& variables, const std::string& held_field,
                                   const std::vector<int>& offsets, double change) {
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
  if (!split(held_field, held_list, held)) return {};
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

bool buildable_at_t_star(const Design& design, TStarCollisions* collisions) {
  if (!all_panels_simple(design)) return false;
  return collisions ? !collisions->check(design) : !self_intersection_at_t_star(design);
}

std::optional<Projection> project_buildable(const json& preset, const ProjectionOptions& options) {
  const Clock::time_point start = Clock::now();
  Projection out;
  auto collides = [&](const Design& design) {
    return options.collisions ? options.collisions->check(design).has_value() : self_intersection_at_t_star(design).has_value();
  };
  Design input = design_from_json(preset);
  ++out.evaluations;
  const bool simple = all_panels_simple(input);  // (the collision check at t* costs far more: only then)
  if (simple && !collides(input)) {
    out.preset = preset;
    out.how = "already";
    out.design.emplace(std::move(input));
    return out;
  }
  RepairOptions search;
  search.t_star_margin = 0.0;  // a drag may take t* towards a limit (only repair keeps it away)
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
  if (options.held_change != 0.0 && !options.fixed.empty()) {
    for (const std::vector<int>& offsets : std::vector<std::vector<int>>{{-1}, {1}, {-1, 1}, {-2, -1, 1, 2}}) {
      std::vector<double> d = neighbour_line(*variables, pointer_field(json::json_pointer(options.fixed.at(0))), offsets,
                                             options.held_change);
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
    if (collides(*chosen)) continue;
    std::vector<double> x = line.fields->start();
    for (std::size_t k = 0; k < x.size(); ++k) x[k] += good * line.d[k];
    if (line.fields == &*variables) {
      out.displacement.assign(x.size(), 0.0);
      for (std::size_t k = 0; k < x.size(); ++k) out.displacement[k] = good * line.d[k];
    }
    out.preset = line.fields->preset_at(x);
    out.design.emplace(std::move(*chosen));
    out.moved = true;
    out.how = line.how;
    out.window = line.window;
    return out;
  }
  Problem problem(*variables, search, panels, input.assembly.model_size());
  problem.set_mode(ShapeMode::positive_net, MotionMode::none, 1.0);
  std::vector<double> x = feasible_search(*variables, problem, x0, search, left(), options.max_evaluations);
  problem.set_mode(ShapeMode::exact, MotionMode::none, 1.0);
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
  Design found = design_from_json(out.preset);
  if (!all_panels_simple(found) || collides(found)) return std::nullopt;
  out.design.emplace(std::move(found));
  return out;
}

std::optional<Projection> KeepBuildableDrag::step(const json& preset, const std::string& held, const json& previous,
                                                  ProjectionOptions options) {
  const json& now = preset.at(json::json_pointer(held));
  const double change = now.is_number() && previous.is_number() ? now.get<double>() - previous.get<double>() : 0.0;
  // The held field first (the lines read it there), then what the caller holds too.
  std::vector<std::string> fixed{held};
  for (const std::string& f : options.fixed) {
    if (f != held) fixed.push_back(f);
  }
  options.fixed = std::move(fixed);
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
  if (!options.collisions) options.collisions = &collisions_;
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

}  // namespace phedra
