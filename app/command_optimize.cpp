// phedra optimize PRESET --target NAME=VALUE|NAME>=VALUE|NAME<=VALUE ... [--fit FILE] -o OUT.json
//   [--vary GROUPS] [--no-keep-buildable] [--tol REL] [--max-seconds S] [--start ATLAS.zarr] [--closest FILE] [--json]

#include "commands.h"
#include "number_checks.h"
#include "phedra/mechanics_figures.h"
#include "phedra/report_values.h"
#include "phedra/buildability.h"
#include "phedra/design_preset.h"
#include "phedra/errors.h"
#include "phedra/files.h"
#include "phedra/metamaterial_metrics.h"
#include "phedra/number_format.h"
#include "phedra/optimize.h"
#include "support.h"

#include <filesystem>
#include <memory>
#include <ostream>

namespace phedra::cli {
namespace {

struct OptimizeCommandOptions {
  std::string preset, output, closest, fit, start;
  std::vector<std::string> targets;
  std::string vary = "apex_heights,directions";
  std::string axes = "structural";
  double fit_tolerance = 0.0;
  bool no_keep_buildable = false;
  bool json = false;
  OptimizeOptions optimize;
};

std::string value_text(const std::optional<double>& v) { return v ? format_human(*v) : std::string("undefined"); }


nlohmann::json result_json(const OptimizeResult& r, const std::string& written) {
  nlohmann::json targets = nlohmann::json::array();
  for (const TargetOutcome& t : r.targets) {
    targets.push_back({{"target", t.target}, {"before", optional_json(t.before)}, {"after", optional_json(t.after)},
                       {"met", t.met}, {"error", t.error}});
  }
  nlohmann::json changes = nlohmann::json::array();
  for (const FieldChange& c : r.changes) {
    changes.push_back({{"field", c.field}, {"before", c.before}, {"after", c.after}, {"change", c.change}, {"relative", c.relative}});
  }
  return {{"reached", r.reached},
          {"targets", targets},
          {"buildable", r.buildable},
          {"buildability", r.buildability},
          {"binding", r.binding.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.binding)},
          {"changes", changes},
          {"distance", r.distance},
          {"evaluations", r.evaluations},
          {"seconds", r.seconds},
          {"notes", r.notes},
          {"started_from", r.started_from.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.started_from)},
          {"written", written.empty() ? nlohmann::json(nullptr) : nlohmann::json(written)}};
}

}  // namespace

void add_optimize_command(CLI::App& app, Context& context) {
  auto o = std::make_shared<OptimizeCommandOptions>();
  std::string names;
  for (const std::string& n : figure_names()) names += (names.empty() ? "" : ", ") + n;
  std::string mechanics;
  for (const std::string& n : mechanics_figure_names()) mechanics += (mechanics.empty() ? "" : ", ") + n;
  CLI::App* sub = app.add_subcommand(
      "optimize", "Inverse design: the design nearest the input whose metamaterial figures (phedra metrics) and "
                  "mechanics (phedra mechanics) meet "
                  "targets, buildable over its whole flexion interval (unless --no-keep-buildable); every figure "
                  "printed is recomputed on the written file. Exit 0 reached, 1 not reached (nothing written unless "
                  "--closest), 2 bad input, 3 unwritable output");
  add_preset_argument(sub, o->preset);
  sub->add_option("-t,--target", o->targets,
                  "NAME=VALUE, NAME>=VALUE or NAME<=VALUE (repeatable). NAME: " + names +
                      " (Poisson's ratios at t*, deployment ratios over the interval, t_mu - t_lambda, largest / "
                      "smallest enclosed volume); the mechanics (phedra mechanics, as made: at t* and with the folds "
                      "at rest there): " + mechanics + " (second over first non-rigid eigenvalue, the motion's "
                      "stiffness, the barrier to the second minimum); mechanics.bistable alone: two minima")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  sub->add_option("--fit", o->fit,
                  "A surface to fit: JSON {\"points\": [[x, y, z], ...]} the design at t* should pass near (RMS "
                  "distance after the best rigid motion of the points)");
  sub->add_option("--fit-tol", o->fit_tolerance,
                  "The RMS distance that counts as fitting (model units; default 1 % of the model size)")
      ->check(positive_number());
  sub->add_option("-o,--output", o->output, "The optimized preset (.json); written only when every target is met")->required();
  sub->add_option("--vary", o->vary, "What may change: a comma-separated list of apex_heights, directions, trajectory")
      ->capture_default_str();
  sub->add_flag("--no-keep-buildable", o->no_keep_buildable,
                "Do not require the result to be buildable (by default it is, as phedra check says)");
  sub->add_option("--tol", o->optimize.relative_tolerance,
                  "An equality target is met within this fraction of its value (or 0.01, whichever is larger)")
      ->check(positive_number())
      ->capture_default_str();
  sub->add_option_function<std::string>(
         "--axes", [o](const std::string& name) { o->optimize.axes = parse_metrics_axes(name); },
         "The axes the figures use, as phedra metrics --axes: structural or xyz")
      ->default_str("structural");
  add_size_bound_options(sub, o->optimize.bounds);
  sub->add_option("--max-seconds", o->optimize.max_seconds, "Time for the search; the best found by then is reported")
      ->check(positive_number())
      ->capture_default_str();
  sub->add_option("--seed", o->optimize.seed, "Seed of the perturbed restarts")->capture_default_str();
  sub->add_option("--start", o->start,
                  "A design-space atlas (python3 -m phedra.atlas, docs/atlas.md) of this design: the search starts "
                  "from the best of its 8 rows nearest the targets (or the input, if better)");
  sub->add_option("--closest", o->closest, "When the targets are not reached: write the closest design here (.json)");
  sub->add_flag("--json", o->json, "Print JSON instead of text");
  sub->callback([o, &context] {
    if (std::filesystem::path(o->output).extension() != ".json") {
      throw InvalidInputError("--output", "the optimized preset is written as .json: \"" + o->output + "\"");
    }
    if (!o->closest.empty() && std::filesystem::path(o->closest).extension() != ".json") {
      throw InvalidInputError("--closest", "the closest design is written as .json: \"" + o->closest + "\"");
    }
    for (const std::string& t : o->targets) o->optimize.targets.push_back(FigureTarget::parse(t));
    // Unwritable outputs fail before the search, not a minute after it (nothing is left behind).
    for (const std::string& path : {o->output, o->closest}) {
      if (path.empty()) continue;
      refuse_overwriting_input(path, o->preset);
      AtomicFile probe(path);
    }
    o->optimize.vary = parse_variable_groups(o->vary);
    o->optimize.keep_buildable = !o->no_keep_buildable;
    const LoadedDesign loaded = load_with_preset(context, o->preset);
    if (!o->fit.empty()) {
      FitTarget fit;
      fit.points = FitTarget::read_points(o->fit);
      fit.tolerance = o->fit_tolerance > 0.0 ? o->fit_tolerance : 0.01 * bounded_model_size(loaded.design, o->optimize.bounds);
      o->optimize.fit = fit;
    }
    if (!o->start.empty()) o->optimize.starts = atlas_starts(o->start, o->optimize, 8);
    OptimizeResult r = optimize(loaded.preset, o->optimize);
    const std::string name = loaded.preset.value("name", std::string("unnamed"));
    std::string written;
    if (r.reached) {
      emit(preset_text(named_optimized(r.preset, name, o->vary, r), o->preset), o->output, o->preset, context.out);
      // The figures printed are those of the written file, recomputed: never the optimizer's.
      const Design reread = load_design(o->output);
      r.targets = [&] {
        std::vector<TargetOutcome> again = evaluate_targets(reread, o->optimize);
        for (std::size_t k = 0; k < again.size(); ++k) again[k].before = r.targets[k].before;
        return again;
      }();
      BuildabilityOptions b;
      b.bounds = o->optimize.bounds;
      b.diagnosis.hints = false;
      b.sweep.samples_per_side = 200;  // as the search verified it, and as check sweeps
      const BuildabilityReport report = assess_buildability(reread, nullptr, b);
      r.buildable = report.buildable();
      r.buildability = report.summary();
      bool met = true;
      for (const TargetOutcome& t : r.targets) met = met && t.met;
      if (!met || (o->optimize.keep_buildable && !r.buildable)) {
        std::filesystem::remove(o->output);  // nothing half-true left behind
        r.reached = false;
        r.binding = "the written file did not confirm the search's result (" + r.buildability + ")";
      } else {
        written = o->output;
      }
    } else if (!o->closest.empty()) {
      emit(preset_text(named_optimized(r.preset, name, o->vary, r), o->preset), o->closest, o->preset, context.out);
      written = o->closest;
    }
    if (o->json) {
      context.out << result_json(r, written).dump(2) << '\n';
    } else {
      std::ostream& out = context.out;
      if (r.reached) {
        out << "reached: " << written << " (its figures recomputed from the written file)\n";
      } else {
        out << "not reached: the closest design found" << (written.empty() ? "" : ", written to " + written) << '\n';
      }
      for (const TargetOutcome& t : r.targets) {
        out << "  " << t.target << ": " << value_text(t.before) << " -> " << value_text(t.after) << "  "
            << (t.met ? "met" : "not met (" + format_short(t.error) + " tolerances away)") << '\n';
      }
      out << "buildability: " << r.buildability << '\n';
      if (!r.reached) out << "binds: " << r.binding << '\n';
      out << "changed " << r.changes.size() << " field" << (r.changes.size() == 1 ? "" : "s") << ", distance "
          << format_short(r.distance) << " (relative to the model size)" << (r.changes.empty() ? "" : ":") << '\n';
      for (const FieldChange& c : r.changes) {
        out << "  " << c.field << ": " << human_value(c.before) << " -> " << human_value(c.after) << '\n';
      }
      if (!written.empty()) out << "wrote " << written << '\n';
      if (!r.reached && written.empty()) out << "nothing written (--closest FILE writes the closest design)\n";
      for (const std::string& note : r.notes) out << "note: " << note << '\n';
      if (!o->start.empty()) out << "started from: " << (r.started_from.empty() ? "the input (better than the atlas's rows)" : r.started_from + " of " + o->start) << '\n';
      out << "search: " << r.evaluations << " designs built, " << format_short(r.seconds) << " s\n";
    }
    context.exit_code = r.reached ? 0 : static_cast<int>(ExitCode::check_failed);
  });
}

}  // namespace phedra::cli
