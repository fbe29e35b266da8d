#include "phedra/repair.h"

#include "repair_search.h"

#include "phedra/assembly_check.h"
#include "phedra/design_preset.h"
#include "phedra/errors.h"
#include "phedra/field_hints.h"
#include "phedra/self_intersection.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

namespace phedra {
namespace {

using json = nlohmann::json;
using namespace repair_search;

/// The buildability the result is judged by: the report itself, 200 samples a side.
BuildabilityReport verify(const json& preset, const SizeBounds& bounds, bool sweep = true) {
  BuildabilityOptions options;
  options.bounds = bounds;
  options.sweep_motion = sweep;
  options.diagnosis.hints = false;
  options.sweep.samples_per_side = 200;
  return assess_buildability(design_from_json(preset), nullptr, options);
}

/// Starts from a collision at t*'s first-order hints (field_hints.h,
/// collision_hints: the change of one field that opens the shut hinge or parts
/// the panels): x with a hinted length variable moved 1.5 and 3 times its hint
/// (past the first-order change, which only reaches the contact). Empty when x
/// does not collide at t* or no hinted field varies.
std::vector<std::vector<double>> collision_hint_starts(const DesignVariables& variables, const std::vector<double>& x) {
  std::vector<std::vector<double>> out;
  try {
    const json preset = variables.preset_at(x);
    const Design d = design_from_json(preset);
    const std::optional<Collision> c = self_intersection_at_t_star(d);
    if (!c) return out;
    for (const FieldHint& h : collision_hints(preset, d, *c)) {
      for (std::size_t k = 0; k < variables.size(); ++k) {
        const DesignVariable& v = variables.variables()[k];
        if (v.fixed || v.kind != DesignVariable::Kind::length || v.field != h.field) continue;
        for (const double times : {1.5, 3.0}) {
          std::vector<double> y = x;
          y[k] += times * h.change;
          out.push_back(std::move(y));
        }
      }
    }
  } catch (const Error&) {
  }
  return out;
}

/// What `phedra check` says of the geometry (planarity, isometry, closure and
/// the reproduction at t*, its default samples): a result is written only when
/// the file will pass it too.
bool geometry_passes(const json& preset) {
  try {
    return check_assembly(design_from_json(preset).assembly).passed();
  } catch (const Error&) {
    return false;
  }
}

}  // namespace

/// Every number that differs between two presets, as fields (directions as turns).
std::vector<FieldChange> changes_between(const json& before, const json& after, double size,
                                         const json::json_pointer& at) {
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

namespace {

/// Two failed searches: `into` takes `other`'s closest design when it is closer
/// (fewer panels not simple, then a wider buildable part).
void take_closest_if_closer(RepairResult& into, const RepairResult& other) {
  const std::size_t a = into.after.invalid.size(), b = other.after.invalid.size();
  if (b < a || (b == a && other.closest_fraction > into.closest_fraction)) {
    into.after = other.after;
    into.closest = other.closest;
    into.closest_preset = other.closest_preset;
    into.closest_fraction = other.closest_fraction;
  }
}

/// One search varying options.vary (repair() escalates).
RepairResult repair_varying(const json& preset, const RepairOptions& options) {
  const Clock::time_point start = Clock::now();
  RepairResult r;
  const Design input = design_from_json(preset);
  const double size = bounded_model_size(input, options.bounds);  // an oversized panel's length would swamp it
  const DesignVariables variables(preset, options.vary, size, options.fixed);  // bad --vary: an error even when nothing is to do
  r.notes = variables.notes();
  r.before = verify(preset, options.bounds);
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
  Problem problem(variables, options, panels, size, t_star_margin(input.assembly));
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
    json at;
    try {
      at = variables.preset_at(x);
      c.report = verify(at, options.bounds);
    } catch (const Error&) {
      return false;
    }
    c.fraction = c.report.panels_simple() ? buildable_fraction(c.report) : -1.0;
    if (!closest || c.report.invalid.size() < closest->report.invalid.size() ||
        (c.report.invalid.size() == closest->report.invalid.size() && c.fraction > closest->fraction)) {
      closest = c;
    }
    if (meets(c.report, required)) {  // only the required part makes a result
      if (!geometry_passes(at)) return false;  // one phedra check would refuse (t* at a limit: ill-conditioned)
      if (!best || c.distance < best->distance) best = c;
      return true;
    }
    if (c.fraction >= 0.0 && (!best_partial || c.fraction > best_partial->fraction ||
                              (c.fraction == best_partial->fraction && c.distance < best_partial->distance))) {
      best_partial = c;
    }
    return meets(c.report, fraction_wanted);  // a narrower part searched for the closest design
  };
  auto time_left = [&] { return options.max_seconds - seconds_since(start); };
  const std::vector<double> x0 = variables.start();
  consider(x0, required);  // the input itself: the widest part to beat

  // Stage 1, panel shapes and the configuration at t* (cheap: no sweep): from
  // the input and from perturbed starts (the simple designs need not form one
  // connected set), a design with every panel simple (the positive net first,
  // the exact rule when that fails), moved towards the input (bisection) and to
  // the nearest one; then free of collisions at t* the same way.
  std::optional<Candidate> closest_shapes;  // the fewest panels not simple, when no start succeeds
  auto simple_from = [&](const std::vector<double>& from) -> std::optional<std::vector<double>> {
    ++r.starts;
    std::vector<double> x = from;
    problem.set_mode(ShapeMode::exact, MotionMode::none, required);
    if (total_violation(problem, x) > 0.0) {
      problem.set_mode(ShapeMode::positive_net, MotionMode::none, required);
      x = feasible_search(variables, problem, x, options, time_left(), options.max_evaluations);
      problem.set_mode(ShapeMode::exact, MotionMode::none, required);
      if (total_violation(problem, x) > 0.0) x = feasible_search(variables, problem, from, options, time_left(), options.max_evaluations);
      if (total_violation(problem, x) > 0.0) {
        try {
          Candidate c{x, variables.distance(x), -1.0, verify(variables.preset_at(x), options.bounds, false)};
          if (!closest_shapes || c.report.invalid.size() < closest_shapes->report.invalid.size()) closest_shapes = c;
        } catch (const Error&) {
        }
        return std::nullopt;
      }
      x = towards(problem, x, x0);
      x = local_search(variables, problem, x, options, time_left(), options.max_evaluations);
    }
    // Then the configuration at t* free of collisions too (one snapshot a design:
    // still cheap): most designs that fail collide there, not later in the motion.
    problem.set_mode(ShapeMode::exact, MotionMode::t_star, required);
    if (total_violation(problem, x) > 0.0) {
      std::vector<double> free = feasible_search(variables, problem, x, options, time_left(), options.max_evaluations);
      if (total_violation(problem, free) > 0.0) {
        // Stalled (the summed depths have flat stretches): from where the
        // collision's own hints point, the field that opens it moved past them.
        // Two levels: a start that frees this collision may meet the next one,
        // whose hints are followed in turn (at most 12 searches).
        std::vector<std::vector<double>> starts = collision_hint_starts(variables, x);
        // A third of the evaluations each: a hint that works frees the collision
        // quickly, and twelve full searches would cost more than the rest of stage 1.
        std::size_t level_end = starts.size(), tried = 0;
        const std::size_t hint_evaluations = std::max<std::size_t>(1, options.max_evaluations / 3);
        for (std::size_t k = 0; k < starts.size() && tried < 12 && time_left() > 0.0; ++k, ++tried) {
          free = feasible_search(variables, problem, starts[k], options, time_left(), hint_evaluations);
          if (total_violation(problem, free) == 0.0) break;
          if (k < level_end) {
            for (std::vector<double>& y : collision_hint_starts(variables, free)) starts.push_back(std::move(y));
          }
        }
      }
      if (total_violation(problem, free) == 0.0) {
        free = towards(problem, free, x0);
        x = local_search(variables, problem, free, options, time_left(), options.max_evaluations);
      }  // else the simple design, colliding at t*: stage 2 tries it with the motion
    }
    return x;
  };
  // Stage 2, the motion: from a simple design, no collision over the required
  // part, then towards the input and to the nearest such design.
  auto motion_from = [&](std::vector<double> x, double fraction) {
    problem.set_mode(ShapeMode::exact, MotionMode::range, fraction);
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
  if (!best && time_left() > 0.0) {
    // The local searches from the input stalled (on random designs mostly at a
    // collision at t*): scattered starts, each judged by shapes and t* at once.
    problem.set_mode(ShapeMode::exact, MotionMode::t_star, required);
    if (std::optional<std::vector<double>> found =
            scatter_search(variables, problem, x0, options.scatter_samples, 3, rng, options, 0.5 * time_left())) {
      std::vector<double> x = towards(problem, *found, x0);
      x = local_search(variables, problem, x, options, time_left(), options.max_evaluations);
      simple.insert(simple.begin(), x);
      motion_from(x, required);
    }
  }
  if (!best && options.search_widest && !simple.empty()) {
    for (const double fraction : {0.75, 0.5, 0.25, 0.0}) {
      if (fraction >= required || time_left() <= 0.0) continue;
      if (motion_from(best_partial ? best_partial->x : simple.front(), fraction)) break;
    }
  }
  // The widest part found is the closest design, not a result (the required part was not reached).
  if (!best && best_partial && best_partial->fraction > 0.0) closest = best_partial;
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
          const json tidied = variables.preset_at(tidy);
          const BuildabilityReport report = verify(tidied, options.bounds);
          if (report.panels_simple() && buildable_fraction(report) >= best->fraction - 1e-12 && geometry_passes(tidied)) {
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
    r.closest_fraction = closest && closest->fraction > 0.0 ? closest->fraction : 0.0;
    const BuildabilityReport& c = r.after;
    if (!c.panels_simple()) {
      r.closest = "no design near the input has every panel simple: at best " + std::to_string(c.invalid.size()) +
                  " stay not simple (panels " + c.invalid_list() + ")";
    } else if (c.motion.at_t_star) {
      r.closest = "every panel can be made simple, but the configuration at t* then collides: " +
                  describe(*c.motion.at_t_star, c.members > 1);
    } else {
      const double percent = 100.0 * buildable_fraction(c);
      r.closest = "the best design found is buildable over " +
                  (percent >= 1.0 ? std::to_string(static_cast<int>(percent)) + " %" : std::string("less than 1 %")) +
                  " of the way from t* to the limits only";
    }
  }
  r.seconds = seconds_since(start);
  return r;
}

}  // namespace

namespace {

/// The nearest design (escalated when it must be).
RepairResult nearest_design(const json& preset, const RepairOptions& options);

/// RepairObjective::fields: from the nearest design's changes, largest first,
/// vary only the top 1, 2, 4, ... (every other field held) until a search meets
/// the same requirement; the result changes fewer fields, or is the nearest.
RepairResult fewest_fields(const json& preset, const RepairOptions& options, RepairResult nearest) {
  nearest.nearest_changes = nearest.changes.size();
  if (!nearest.found || nearest.already_buildable || nearest.changes.size() <= 1) return nearest;
  const Clock::time_point start = Clock::now();
  std::vector<FieldChange> ranked = nearest.changes;
  std::stable_sort(ranked.begin(), ranked.end(), [](const FieldChange& a, const FieldChange& b) { return a.relative > b.relative; });
  const Design input = design_from_json(preset);
  const DesignVariables variables(preset, nearest.varied, bounded_model_size(input, options.bounds), options.fixed);
  RepairResult best = nearest;
  std::size_t tried = 0;
  for (std::size_t m = 1; m < best.changes.size(); m *= 2) {
    const double left = options.max_seconds - seconds_since(start);
    if (left <= 0.0) break;
    std::vector<std::string> varied;
    for (std::size_t k = 0; k < m && k < ranked.size(); ++k) varied.push_back(ranked[k].field);
    RepairOptions subset = options;
    subset.vary = nearest.varied;
    subset.escalate = false;
    subset.objective = RepairObjective::distance;
    subset.required_fraction = nearest.fraction;
    subset.search_widest = false;
    subset.max_seconds = left;
    for (const DesignVariable& v : variables.variables()) {
      if (std::find(varied.begin(), varied.end(), v.field) == varied.end()) subset.fixed.push_back(v.pointer);
    }
    ++tried;
    RepairResult r = repair_varying(preset, subset);
    best.evaluations += r.evaluations;
    best.starts += r.starts;
    if (r.found && r.fraction >= nearest.fraction - 1e-12 && r.changes.size() < best.changes.size()) {
      const std::size_t evaluations = best.evaluations, starts = best.starts;
      r.varied = nearest.varied;
      r.escalated = nearest.escalated;
      r.notes = nearest.notes;
      r.evaluations = evaluations;
      r.starts = starts;
      best = std::move(r);
      break;
    }
  }
  best.nearest_changes = nearest.changes.size();
  best.seconds = nearest.seconds + seconds_since(start);
  best.notes.push_back("--objective fields: " + std::to_string(best.changes.size()) + " fields changed, the nearest design changes " +
                       std::to_string(nearest.changes.size()) + " (" + std::to_string(tried) + " searches with fewer fields)");
  return best;
}

}  // namespace

RepairResult repair(const json& preset, const RepairOptions& options) {
  RepairResult nearest = nearest_design(preset, options);
  // Nothing found and time left: the searches again from other random starts
  // (the perturbed restarts and the scattered designs draw from the seed).
  for (unsigned retry = 1; retry <= options.retries && !nearest.found && !nearest.already_buildable &&
                           nearest.before.self_crossing_members.empty() && options.max_seconds - nearest.seconds > 1.0;
       ++retry) {
    RepairOptions again = options;
    again.seed = options.seed + retry;
    again.max_seconds = options.max_seconds - nearest.seconds;
    RepairResult r = nearest_design(preset, again);
    r.seconds += nearest.seconds;
    r.evaluations += nearest.evaluations;
    r.starts += nearest.starts;
    if (r.found) {
      r.notes.push_back("found from other random starts (search " + std::to_string(retry + 1) + ")");
      nearest = std::move(r);
    } else {
      nearest.seconds = r.seconds;
      nearest.evaluations = r.evaluations;
      nearest.starts = r.starts;
      take_closest_if_closer(nearest, r);
    }
  }
  if (options.objective == RepairObjective::fields) return fewest_fields(preset, options, nearest);
  RepairResult r = nearest;
  r.nearest_changes = r.changes.size();
  return r;
}

namespace {

RepairResult nearest_design(const json& preset, const RepairOptions& options) {
  if (!(options.required_fraction >= 0.0 && options.required_fraction <= 1.0)) {
    throw InvalidInputError("--require", "the buildable part must be a fraction in [0, 1]");
  }
  const bool trajectory = std::find(options.vary.begin(), options.vary.end(), VariableGroup::trajectory) !=
                          options.vary.end();
  const bool may_escalate = options.escalate && !trajectory;
  RepairOptions first = options;
  if (may_escalate) first.max_seconds = 0.6 * options.max_seconds;  // the rest for the trajectory
  RepairResult r = repair_varying(preset, first);
  r.varied = options.vary;
  if (r.found || r.already_buildable || !may_escalate || !r.before.self_crossing_members.empty()) return r;
  // What may vary did not suffice: the trajectory too (it reaches what heights
  // and turns cannot: a segment nearly in its profile plane, a reversed one).
  RepairOptions wider = options;
  wider.vary.push_back(VariableGroup::trajectory);
  wider.max_seconds = std::max(1e-3, options.max_seconds - r.seconds);
  RepairResult e = repair_varying(preset, wider);
  e.varied = wider.vary;
  e.escalated = true;
  e.seconds += r.seconds;
  e.evaluations += r.evaluations;
  e.starts += r.starts;
  std::string names;
  for (VariableGroup g : options.vary) names += (names.empty() ? "" : ", ") + to_string(g);
  e.notes.push_back(e.found ? names + " alone could not make it buildable: the trajectory was varied too"
                            : "neither " + names + " nor the trajectory as well could make it buildable");
  if (!e.found) take_closest_if_closer(e, r);  // the closer of the two failures
  return e;
}

}  // namespace

}  // namespace phedra
