#include "phedra/optimize.h"
#include "phedra/mechanics_figures.h"

#include "repair_search.h"

#include "phedra/assembly_check.h"
#include "phedra/buildability.h"
#include "phedra/design_preset.h"
#include "phedra/errors.h"
#include "phedra/metamaterial_metrics.h"
#include "phedra/number_format.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace phedra {

using namespace repair_search;

FigureTarget FigureTarget::parse(const std::string& text) {
  FigureTarget t;
  if (text == "mechanics.bistable") {  // a property: two minima in the energy landscape
    t.name = text;
    t.kind = Kind::at_least;
    t.value = 1.0;
    return t;
  }
  std::size_t at = text.find(">=");
  std::size_t width = 2;
  if (at != std::string::npos) {
    t.kind = Kind::at_least;
  } else if ((at = text.find("<=")) != std::string::npos) {
    t.kind = Kind::at_most;
  } else if ((at = text.find('=')) != std::string::npos) {
    width = 1;
  } else {
    throw InvalidInputError("--target", "\"" + text + "\": expected NAME=VALUE, NAME>=VALUE or NAME<=VALUE");
  }
  t.name = text.substr(0, at);
  std::vector<std::string> names = figure_names();
  names.insert(names.end(), mechanics_figure_names().begin(), mechanics_figure_names().end());
  if (std::find(names.begin(), names.end(), t.name) == names.end()) {
    std::string known;
    for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
    throw InvalidInputError("--target", "unknown figure \"" + t.name + "\" in \"" + text + "\"; known: " + known +
                                            " (and --fit FILE for a surface)");
  }
  const std::string value = text.substr(at + width);
  std::size_t used = 0;
  try {
    t.value = std::stod(value, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != value.size() || !std::isfinite(t.value)) {
    throw InvalidInputError("--target", "\"" + text + "\": the value \"" + value + "\" is not a number");
  }
  if (t.name == "mechanics.bistable") {
    throw InvalidInputError("--target", "\"" + text + "\": mechanics.bistable is a property: write it alone "
                                                        "(--target mechanics.bistable)");
  }
  return t;
}

std::string FigureTarget::to_string() const {
  if (name == "mechanics.bistable") return name;
  return name + (kind == Kind::equal ? "=" : kind == Kind::at_least ? ">=" : "<=") + format_human(value);
}

namespace {

double tolerance_of(const FigureTarget& t, const OptimizeOptions& o) {
  return std::max(o.relative_tolerance * std::abs(t.value), o.absolute_tolerance);
}

/// The signed shortfall over the tolerance: 0 when met (an equality within it).
double shortfall(const FigureTarget& t, double value, const OptimizeOptions& o) {
  const double e = (value - t.value) / tolerance_of(t, o);
  switch (t.kind) {
    case FigureTarget::Kind::equal: return std::abs(e) <= 1.0 ? 0.0 : e;
    case FigureTarget::Kind::at_least: return std::min(e, 0.0);
    case FigureTarget::Kind::at_most: return std::max(e, 0.0);
  }
  return 0.0;
}

bool needs_interval(const OptimizeOptions& o) {
  return std::any_of(o.targets.begin(), o.targets.end(), [](const FigureTarget& t) {
    return !is_mechanics_figure(t.name) && figure_needs_interval(t.name);
  });
}

constexpr double undefined_error = 500.0;  ///< a figure that is undefined on a design: far from any goal

}  // namespace

std::vector<TargetOutcome> evaluate_targets(const Design& design, const OptimizeOptions& options) {
  std::vector<TargetOutcome> out;
  std::vector<std::string> mechanics;
  bool metrics = false;
  for (const FigureTarget& t : options.targets) {
    if (is_mechanics_figure(t.name)) {
      mechanics.push_back(t.name);
    } else {
      metrics = true;
    }
  }
  std::optional<MetricsReport> report;
  if (metrics) {
    MetricsOptions m;
    m.samples = needs_interval(options) ? options.samples : 2;
    m.axes = options.axes;
    report = metamaterial_metrics(design, m);
  }
  std::optional<MechanicsFigures> figures;
  if (!mechanics.empty()) figures = mechanics_figures(design, mechanics);
  for (const FigureTarget& t : options.targets) {
    TargetOutcome o;
    o.target = t.to_string();
    o.after = figures && is_mechanics_figure(t.name) ? figures->figure(t.name) : report->figure(t.name);
    if (o.after && !std::isfinite(*o.after)) o.after.reset();
    if (t.name == "mechanics.bistable" || (t.name == "mechanics.barrier" && !figures->bistable)) {
      // Not yet bistable: how far, by the landscape's continuous measure (the search's slope).
      o.met = t.name == "mechanics.bistable" && figures->bistable;
      o.error = o.met ? 0.0 : (t.name == "mechanics.barrier" ? 10.0 : 1.0) + 10.0 * std::max(0.0, -figures->bistability);
    } else {
      o.error = o.after ? std::abs(shortfall(t, *o.after, options)) : undefined_error;
      o.met = o.after && o.error == 0.0;
    }
    out.push_back(o);
  }
  if (options.fit) {
    TargetOutcome o;
    o.target = "fit<=" + format_human(options.fit->tolerance);
    o.after = fit_distance(design, options.fit->points, options.fit->start.get());
    o.error = std::max(*o.after / options.fit->tolerance - 1.0, 0.0);
    o.met = o.error == 0.0;
    out.push_back(o);
  }
  return out;
}

namespace {

/// Buildable as `phedra check` says it: the whole interval swept, 200 samples a side.
BuildabilityReport verify_buildable(const Design& design, const SizeBounds& bounds) {
  BuildabilityOptions options;
  options.bounds = bounds;
  options.diagnosis.hints = false;
  options.sweep.samples_per_side = 200;
  return assess_buildability(design, nullptr, options);
}

/// The search's view: the targets' squared errors (a fit's relative distance
/// squared: minimised beyond its tolerance too), the constraints' exact penalty,
/// a small pull towards the input.
class TargetSearch {
 public:
  TargetSearch(const DesignVariables& variables, const OptimizeOptions& options, Problem& problem)
      : variables_(variables), options_(options), problem_(problem) {}

  bool constrained = true;
  std::size_t evaluations = 0, failures = 0;
  std::string last_failure;

  double value(const std::vector<double>& x) {
    ++evaluations;
    double sum = 0.0;
    try {
      const Design d = design_from_json(variables_.preset_at(x));
      const std::vector<TargetOutcome> outcomes = evaluate_targets(d, options_);
      // In units of 50 tolerances (about the value itself), so that the
      // constraints' penalty outweighs any target; an equality target is aimed at
      // its value itself (no dead zone: the result lands near the middle of the
      // tolerance, not on its edge), the fit at distance 0.
      for (std::size_t k = 0; k < outcomes.size(); ++k) {
        const TargetOutcome& o = outcomes[k];
        double e = o.error;
        if (k < options_.targets.size() && o.after) {
          // An inequality is aimed a quarter tolerance inside its bound (a value on
          // the bound itself is met or not by rounding).
          const FigureTarget& t = options_.targets[k];
          const double tol = tolerance_of(t, options_);
          e = t.kind == FigureTarget::Kind::equal      ? (*o.after - t.value) / tol
              : t.kind == FigureTarget::Kind::at_least ? std::min((*o.after - t.value) / tol - 0.25, 0.0)
                                                       : std::max((*o.after - t.value) / tol + 0.25, 0.0);
        } else if (k == options_.targets.size() && options_.fit) {
          e = *o.after / options_.fit->tolerance;
        }
        e /= 50.0;
        sum += e * e;
      }
    } catch (const Error& e) {
      ++failures;
      last_failure = e.what();
      return 1e6;
    }
    // The constraints first (an extreme barrier: any design that meets them beats
    // any that does not, so from a buildable input the search stays among
    // buildable designs), then the targets, then a small pull towards the input.
    const double violation = constrained ? total_violation(problem_, x) : 0.0;
    if (violation > 0.0) return 1e3 * (1.0 + violation) + 1e-3 * sum;
    const double distance = variables_.distance(x);
    return sum + 1e-3 * distance * distance;
  }

 private:
  const DesignVariables& variables_;
  const OptimizeOptions& options_;
  Problem& problem_;
};

struct SearchData {
  TargetSearch* search;
  std::vector<double> best;
  double best_value = std::numeric_limits<double>::infinity();
};

double nlopt_value(unsigned n, const double* x, double* /*gradient*/, void* data) {
  SearchData& s = *static_cast<SearchData*>(data);
  const std::vector<double> v(x, x + n);
  const double value = s.search->value(v);
  if (value < s.best_value) {
    s.best_value = value;
    s.best = v;
  }
  return value;
}

}  // namespace

namespace {

/// One search over a set of variables: local searches (Subplex) from the best
/// point so far, perturbed restarts when they stall, every end point verified.
class TargetRun {
 public:
  TargetRun(const nlohmann::json& preset, const OptimizeOptions& options, const DesignVariables& variables,
            const RepairOptions& repair_options, std::size_t panels, double size)
      : options_(options),
        variables_(variables),
        repair_options_(repair_options),
        problem_(variables, repair_options, panels, size),
        search_(variables, options, problem_) {
    (void)preset;
    problem_.set_mode(ShapeMode::exact, MotionMode::t_star, 1.0);
    search_.constrained = options.keep_buildable;
  }

  TargetSearch& search() { return search_; }
  Problem& problem() { return problem_; }

  /// All targets met by the metrics, the geometry sound as `phedra check` says
  /// (planarity, isometry, closure: a design next to a bifurcation inside its
  /// interval is not), and (keep_buildable) buildable by the report.
  bool verified(const std::vector<double>& x) {
    try {
      const Design d = design_from_json(variables_.preset_at(x));
      for (const TargetOutcome& o : evaluate_targets(d, options_)) {
        if (!o.met) return false;
      }
      if (!check_assembly(d.assembly, {}).passed()) return false;
      if (!options_.keep_buildable) return true;
      if (verify_buildable(d, options_.bounds).buildable()) return true;
      // Reached, but the motion collides away from t*: the sweep joins the constraints.
      problem_.set_mode(ShapeMode::exact, MotionMode::range, 1.0);
      return false;
    } catch (const Error&) {
      return false;
    }
  }

  /// Searches from x for `seconds`; the verified answer, if any. `best` is the
  /// best point by the search's own value (kept for the report when none is).
  std::optional<std::vector<double>> run(std::vector<double> x, double seconds, std::mt19937_64& rng,
                                         std::vector<double>& best) {
    const Clock::time_point start = Clock::now();
    best = x;
    double best_value = search_.value(best);
    if (verified(best)) return best;
    std::normal_distribution<double> normal;
    int stalls = 0;
    for (int round = 0; round < 60 && seconds_since(start) < seconds; ++round) {
      x = best;
      if (stalls > 0) {  // perturbed restarts about the best so far, wider as they fail
        const double radius = std::min(0.3, 0.03 * stalls);
        for (std::size_t k = 0; k < x.size(); ++k) {
          if (!variables_.variables()[k].fixed) x[k] += radius * variables_.variables()[k].scale * normal(rng);
        }
      }
      nlopt::opt opt(nlopt::LN_SBPLX, static_cast<unsigned>(variables_.size()));
      configure(opt, variables_, x, repair_options_, seconds - seconds_since(start));
      opt.set_maxeval(800);
      opt.set_ftol_abs(1e-10);
      SearchData data{&search_, x, std::numeric_limits<double>::infinity()};
      opt.set_min_objective(nlopt_value, &data);
      run_opt(opt, x);
      if (data.best_value < best_value - 1e-3 * std::abs(best_value)) {
        stalls = 0;
      } else {
        ++stalls;
      }
      if (data.best_value < best_value) {
        best_value = data.best_value;
        best = data.best;
      }
      if (verified(data.best)) return data.best;
    }
    return std::nullopt;
  }

 private:
  const OptimizeOptions& options_;
  const DesignVariables& variables_;
  const RepairOptions& repair_options_;
  Problem problem_;
  TargetSearch search_;
};

}  // namespace

OptimizeResult optimize(const nlohmann::json& preset, const OptimizeOptions& given) {
  const Clock::time_point start = Clock::now();
  OptimizeOptions options = given;
  if (options.targets.empty() && !options.fit) {
    throw InvalidInputError("--target", "nothing to optimize: give at least one --target NAME=VALUE (or --fit FILE)");
  }
  if (!(options.max_seconds > 0.0)) throw InvalidInputError("--max-seconds", "must be positive");
  const Design input = design_from_json(preset);
  const double size = bounded_model_size(input, options.bounds);
  if (options.fit) {
    // The best alignment of the points to the input, found once (many starts); each
    // design of the search is then fitted from the one before.
    options.fit->start = std::make_shared<Mat3>(best_fit(input, options.fit->points).turn);
  }
  const DesignVariables variables(preset, options.vary, size, options.fixed);
  RepairOptions repair_options;
  // Figures move fastest near the flexion limits, so targets may need t* there:
  // allowed (every result passes phedra check's geometry, verified below).
  repair_options.t_star_margin = 0.0;
  repair_options.bounds = options.bounds;
  std::size_t panels = 0;
  for (std::size_t m = 0; m < input.assembly.member_count(); ++m) panels += input.assembly.topology(m).face_count();
  TargetRun main(preset, options, variables, repair_options, panels, size);
  TargetSearch& search = main.search();

  OptimizeResult r;
  r.notes = variables.notes();
  const std::vector<TargetOutcome> before = evaluate_targets(input, options);
  auto time_left = [&] { return options.max_seconds - seconds_since(start); };
  std::mt19937_64 rng(options.seed);
  const double search_share = options.keep_buildable ? 0.8 : 1.0;  // the rest: what binds, when not reached
  std::vector<double> best;
  // From the input, or the best of the given starts (an atlas's rows) by the search's own value.
  std::vector<double> first = variables.start();
  if (!options.starts.empty()) {
    double first_value = search.value(first);
    for (const auto& [label, start_preset] : options.starts) {
      std::vector<double> x = variables.values_of(start_preset, "--start");
      for (std::size_t k = 0; k < x.size(); ++k) {
        if (variables.variables()[k].fixed) x[k] = variables.variables()[k].start;
      }
      const double value = search.value(x);
      if (value < first_value) {
        first_value = value;
        first = x;
        r.started_from = label;
      }
    }
  }
  std::optional<std::vector<double>> answer =
      main.run(first, time_left() - (1.0 - search_share) * options.max_seconds, rng, best);
  std::size_t tidy_evaluations = 0;
  if (answer) {
    // Tidy: the search moves every variable a little. Changes below a share of
    // each variable's scale go back to the input, the rest searched again with
    // them held (largest share first); the first that still meets everything is kept.
    for (const double share : {0.02, 0.005, 0.001}) {
      if (time_left() <= 0.0) break;
      std::vector<std::string> held = options.fixed;
      std::vector<double> x = *answer;
      std::size_t reset = 0;
      for (std::size_t k = 0; k < x.size(); ++k) {
        const DesignVariable& v = variables.variables()[k];
        if (v.fixed || x[k] == v.start) continue;
        if (std::abs(x[k] - v.start) < share * v.scale) {
          x[k] = v.start;
          held.push_back(v.pointer);
          ++reset;
        }
      }
      if (reset == 0) continue;
      const DesignVariables fewer(preset, options.vary, size, held);
      TargetRun tidy(preset, options, fewer, repair_options, panels, size);
      std::vector<double> unused;
      const std::optional<std::vector<double>> kept = tidy.run(x, std::min(time_left(), 0.25 * options.max_seconds), rng, unused);
      tidy_evaluations += tidy.search().evaluations;
      if (kept) {
        answer = kept;
        break;
      }
    }
  }
  r.reached = answer.has_value();
  const std::vector<double> result_x = answer ? *answer : best;
  r.preset = variables.preset_at(result_x);
  r.distance = variables.distance(result_x);
  r.changes = changes_between(preset, r.preset, size);
  const Design result = design_from_json(r.preset);
  r.targets = evaluate_targets(result, options);
  for (std::size_t k = 0; k < r.targets.size() && k < before.size(); ++k) r.targets[k].before = before[k].after;
  const BuildabilityReport b = verify_buildable(result, options.bounds);
  r.buildable = b.buildable();
  r.buildability = b.summary();

  if (!r.reached) {
    // Which target binds, and what stops it: the same search without the
    // buildability constraints tells whether they are what holds it back.
    const auto worst = std::max_element(r.targets.begin(), r.targets.end(),
                                        [](const TargetOutcome& a, const TargetOutcome& c) { return a.error < c.error; });
    double total = 0.0;
    for (const TargetOutcome& o : r.targets) total += o.error * o.error;
    std::string why;
    if (total == 0.0) {
      r.binding = "buildability binds: the designs found that meet every target are not buildable (the closest: " +
                  r.buildability + ")";
    } else {
      if (options.keep_buildable && time_left() > 0.0) {
        search.constrained = false;
        std::vector<double> x = best;
        nlopt::opt opt(nlopt::LN_SBPLX, static_cast<unsigned>(variables.size()));
        configure(opt, variables, x, repair_options, std::max(0.5, time_left()));
        opt.set_maxeval(2000);
        SearchData data{&search, x, std::numeric_limits<double>::infinity()};
        opt.set_min_objective(nlopt_value, &data);
        run_opt(opt, x);
        try {
          const Design free = design_from_json(variables.preset_at(data.best));
          double free_total = 0.0;
          bool met = true;
          for (const TargetOutcome& o : evaluate_targets(free, options)) {
            free_total += o.error * o.error;
            met = met && o.met;
          }
          if (met || free_total < 0.25 * total) {
            why = std::string("buildability: without it the targets are ") + (met ? "reached" : "closer") +
                  " (that design: " + verify_buildable(free, options.bounds).summary() + ")";
          }
        } catch (const Error&) {
        }
      }
      if (why.empty() && search.failures * 3 > search.evaluations) {
        why = "a flexion limit or an input assumption: " + std::to_string(search.failures) + " of " +
              std::to_string(search.evaluations) + " designs tried do not build (the last: " + search.last_failure + ")";
      }
      if (why.empty()) why = "the varied fields do not reach further (widen --vary, or relax the target)";
      r.binding = worst->target + " is furthest from its goal (" +
                  (worst->after ? format_human(*worst->after) : std::string("undefined")) + "); what stops it: " + why;
    }
  }
  r.evaluations = search.evaluations + tidy_evaluations;
  r.seconds = seconds_since(start);
  return r;
}

nlohmann::json named_optimized(const nlohmann::json& result, const std::string& input_name, const std::string& vary, const OptimizeResult& r) {
  nlohmann::json out = result;
  std::string targets;
  for (const TargetOutcome& o : r.targets) targets += (targets.empty() ? "" : ", ") + o.target;
  out["name"] = input_name + (r.reached ? "-optimized" : "-closest");
  out["description"] = std::string(r.reached ? "Optimized by phedra optimize" : "The closest design phedra optimize found") +
                       " from \"" + input_name + "\" for " + targets + " (varied: " + vary + "): " + r.buildability + ".";
  return out;
}

}  // namespace phedra
