// phedra repair PRESET -o OUT.json [--vary GROUPS] [--require F] [--no-fallback] [--restarts N] [--max-seconds S] [--closest FILE] [--json]

#include "commands.h"
#include "number_checks.h"
#include "phedra/errors.h"
#include "phedra/number_format.h"
#include "phedra/preset.h"
#include "phedra/repair.h"
#include "support.h"
#include "phedra/files.h"

#include <filesystem>
#include <memory>
#include <ostream>

namespace phedra::cli {
namespace {

struct RepairCommandOptions {
  std::string preset;
  std::string output;
  std::string closest;
  std::string vary = "apex_heights,directions";
  std::string objective = "distance";
  RepairOptions repair;
  bool no_fallback = false;
  bool no_escalate = false;
  bool json = false;
};

/// "apex_heights,directions,trajectory": what a result varied, as --vary takes it.
std::string group_list(const std::vector<VariableGroup>& groups) {
  std::string out;
  for (VariableGroup g : groups) out += (out.empty() ? "" : ",") + to_string(g);
  return out;
}

std::string percent(double fraction) { return format_short(100.0 * fraction) + " %"; }

nlohmann::json result_json(const RepairResult& r) {
  nlohmann::json changes = nlohmann::json::array();
  for (const FieldChange& c : r.changes) {
    changes.push_back({{"field", c.field}, {"before", c.before}, {"after", c.after}, {"change", c.change}, {"relative", c.relative}});
  }
  return {{"found", r.found},
          {"already_buildable", r.already_buildable},
          {"fraction", r.fraction},
          {"distance", r.distance},
          {"changes", changes},
          {"before", r.before.file_json()},
          {"after", r.after.file_json()},
          {"evaluations", r.evaluations},
          {"starts", r.starts},
          {"seconds", r.seconds},
          {"notes", r.notes},
          {"varied", group_list(r.varied)},
          {"escalated", r.escalated},
          {"nearest_changes", r.nearest_changes},
          {"closest", r.closest.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.closest)},
          {"closest_fraction", r.found || r.already_buildable ? nlohmann::json(nullptr) : nlohmann::json(r.closest_fraction)}};
}

}  // namespace

void add_repair_command(CLI::App& app, Context& context) {
  auto o = std::make_shared<RepairCommandOptions>();
  CLI::App* sub = app.add_subcommand(
      "repair", "The nearest buildable design: change the preset's apex heights and directions (by default; the "
                "trajectory too when they cannot do it) as little as possible, relative to the model size, until "
                "every panel is simple and the motion is free of collisions over the whole flexion interval (or the "
                "part --require asks); writes the repaired preset and prints what changed; exit 1 when no design "
                "buildable over that part was found (nothing written; --closest writes the closest, e.g. the widest "
                "part reached)");
  add_preset_argument(sub, o->preset);
  sub->add_option("-o,--output", o->output, "The repaired preset (.json); not written when nothing was found")->required();
  sub->add_option("--vary", o->vary, "What may change: a comma-separated list of apex_heights, directions, trajectory")
      ->capture_default_str();
  sub->add_option("--require", o->repair.required_fraction,
                  "The part of the flexion interval that must be buildable: from t* this fraction of the way to each "
                  "limit (1: all of it, 0: t* alone)")
      ->check(number_between(0.0, 1.0))
      ->capture_default_str();
  sub->add_flag("--no-escalate", o->no_escalate,
                "With the default --vary: do not try the trajectory too when the heights and directions cannot do it "
                "(by default it is tried next, and the result says so)");
  sub->add_flag("--no-fallback", o->no_fallback,
                "When the required part cannot be reached, do not search the widest part that can (a faster exit "
                "1; the closest design is then the least bad one found)");
  sub->add_option("--objective", o->objective,
                  "What nearest means: distance (the smallest change, relative to the model size; it may spread "
                  "over many fields) or fields (the fewest fields changed: after the nearest design, searches "
                  "varying only its largest 1, 2, 4, ... changes; up to --max-seconds more)")
      ->check(CLI::IsMember({"distance", "fields"}))
      ->capture_default_str();
  add_size_bound_options(sub, o->repair.bounds);
  sub->add_option("--restarts", o->repair.restarts,
                  "Perturbed starts after the input for the search of simple panels (their set need not be connected)")
      ->check(whole_number_between(0, 1000))
      ->capture_default_str();
  sub->add_option("--max-seconds", o->repair.max_seconds,
                  "Time for the search (half of it at most for the panel shapes); the best found by then is reported")->check(positive_number())->capture_default_str();
  sub->add_option("--closest", o->closest,
                  "When nothing buildable is found: write the closest design to this file (.json), to inspect");
  sub->add_flag("--json", o->json, "Print JSON instead of text");
  sub->callback([o, sub, &context] {
    if (std::filesystem::path(o->output).extension() != ".json") {
      throw InvalidInputError("--output", "the repaired preset is written as .json: \"" + o->output + "\"");
    }
    if (!o->closest.empty() && std::filesystem::path(o->closest).extension() != ".json") {
      throw InvalidInputError("--closest", "the closest design is written as .json: \"" + o->closest + "\"");
    }
    o->repair.vary = parse_variable_groups(o->vary);
    // An explicit --vary is what the user allows; the default may grow to the trajectory.
    o->repair.escalate = !o->no_escalate && sub->count("--vary") == 0;
    o->repair.search_widest = !o->no_fallback;
    o->repair.objective = o->objective == "fields" ? RepairObjective::fields : RepairObjective::distance;
    const LoadedDesign loaded = load_with_preset(context, o->preset);
    const RepairResult r = repair(loaded.preset, o->repair);
    const std::string name = loaded.preset.value("name", std::string("unnamed"));
    if (r.found && !r.already_buildable) {
      emit(preset_text(named_result(r.preset, name, group_list(r.varied), r), o->preset), o->output, o->preset, context.out);
    }
    if (!r.found && !o->closest.empty() && r.closest_preset.is_object()) {
      emit(preset_text(named_result(r.closest_preset, name, group_list(r.varied), r), o->preset), o->closest, o->preset, context.out);
    }
    if (o->json) {
      context.out << result_json(r).dump(2) << '\n';
    } else {
      std::ostream& out = context.out;
      out << "before: " << r.before.summary() << '\n';
      if (r.already_buildable) {
        out << "already buildable as required: nothing to repair, nothing written\n";
      } else if (r.found) {
        out << "after:  " << r.after.summary() << '\n';
        out << "changed " << r.changes.size() << " field" << (r.changes.size() == 1 ? "" : "s");
        if (o->repair.objective == RepairObjective::fields) out << " (the nearest design changes " << r.nearest_changes << ")";
        out << ", distance "
            << format_short(r.distance) << " (relative to the model size, docs/design.md):\n";
        for (const FieldChange& c : r.changes) {
          out << "  " << c.field << ": " << human_value(c.before) << " -> " << human_value(c.after);
          if (c.field.rfind("directions", 0) == 0) {
            out << " (turned " << format_short(c.change) << " degrees)\n";
          } else {
            out << " (" << (c.change >= 0 ? "+" : "") << format_short(c.change) << ", " << format_short(c.relative)
                << " of the model size)\n";
          }
        }
        out << "wrote " << o->output << '\n';
      } else {
        if (r.closest_fraction > 0.0) {  // a narrower part was reached: not a result
          out << "no design buildable over the required part (" << percent(o->repair.required_fraction)
              << " of the way from t* to each limit) found: " << r.closest << "; nothing written";
        } else {
          out << "no buildable design found: " << r.closest << "; nothing written";
        }
        if (!o->closest.empty() && r.closest_preset.is_object()) {
          out << " (the closest design: " << o->closest << ")";
        } else if (r.closest_preset.is_object()) {
          out << " (--closest FILE writes the closest design)";
        }
        out << '\n';
      }
      for (const std::string& note : r.notes) out << "note: " << note << '\n';
      out << "search: " << r.evaluations << " designs built, " << r.starts << " local searches, "
          << format_short(r.seconds) << " s\n";
    }
    context.exit_code = r.found ? 0 : static_cast<int>(ExitCode::check_failed);
  });
}

}  // namespace phedra::cli
