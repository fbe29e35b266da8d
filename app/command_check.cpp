// phedra check PRESET [--samples N] [--tolerance REL] [--closure-only] [--geometry-only] [--json]

#include "commands.h"
#include "number_checks.h"
#include "phedra/assembly_check.h"
#include "phedra/buildability.h"
#include "phedra/errors.h"
#include "phedra/mobility.h"
#include "phedra/number_format.h"
#include "support.h"
#include "phedra/hinge_pins.h"
#include "phedra/check_report.h"
#include "phedra/thick_plates.h"

#include <algorithm>
#include <memory>
#include <ostream>

namespace phedra::cli {
namespace {

struct CheckCommandOptions {
  std::string preset;
  CheckOptions check;
  BuildabilityOptions buildability;
  bool geometry_only = false;
  bool json = false;
  ThicknessOptions thickness;
};

}  // namespace

void add_check_command(CLI::App& app, Context& context) {
  auto options = std::make_shared<CheckCommandOptions>();
  CLI::App* sub = app.add_subcommand(
      "check", "Check planarity, isometry, tube closure and shared vertices over the whole flexion interval (dense "
               "samples, both limits and t*), and buildability: every panel simple (not a bow-tie) and within the size "
               "bounds, the motion "
               "free of collisions, with the cause of every invalid panel and the preset field to change; exit 1 "
               "when a figure exceeds the tolerance or the design is not buildable over the whole interval");
  add_preset_argument(sub, options->preset);
  sub->add_option("--samples", options->check.samples, "Evenly spaced samples of [t_lambda, t_mu], limits included")
      ->check(whole_number_between(2, 10000000))
      ->capture_default_str();
  sub->add_option("--tolerance", options->check.relative_tolerance,
                  "Largest accepted figure, relative to the model size")
      ->check(positive_number())
      ->capture_default_str();
  sub->add_flag_callback(
      "--closure-only", [options] { options->check.shape = false; },
      "The closure check alone: tube closure gaps, shared vertices and the reproduction at t*, without planarity "
      "and isometry of every panel (about three times faster on large arrays)");
  sub->add_flag("--geometry-only", options->geometry_only,
                "The geometric checks alone (planarity, isometry, closure): no buildability, and the exit code "
                "ignores it");
  sub->add_option("--intersection-samples", options->buildability.sweep.samples_per_side,
                  "Buildability: samples from t* to each flexion limit for the collision sweep")
      ->check(whole_number_between(1, 1000000))
      ->capture_default_str();
  add_size_bound_options(sub, options->buildability.bounds);
  add_thickness_options(sub, options->thickness,
                        "Thick panels: plates this thick offset to one side of the panels, bevelled at the hinges; "
                        "reports the thick interval where no two plates collide (inside the buildable interval) and "
                        "which plates end it; exit 1 when the plates collide at t* (docs/design.md, \"Thick panels\")");
  sub->add_flag("--json", options->json, "Print JSON instead of text");
  sub->callback([options, &context] {
    const LoadedDesign loaded = load_with_preset(context, options->preset);
    const AssemblyCheckReport report = check_assembly(loaded.design.assembly, options->check);
    std::optional<BuildabilityReport> buildability;
    if (!options->geometry_only) buildability = assess_buildability(loaded.design, &loaded.preset, options->buildability);
    const bool buildable = !buildability || buildability->buildable();
    std::optional<ThickReport> thick;
    if (std::optional<ThickOptions> plates = thick_options(loaded.design, options->thickness)) {
      if (!buildability) throw InvalidInputError("--thickness", "the thick plates need buildability; drop --geometry-only");
      plates->samples_per_side = options->buildability.sweep.samples_per_side;  // as the zero-thickness sweep
      plates->find_thickest = true;
      thick = check_thickness(loaded.design, *buildability, *plates);
    }
    const bool thick_fits = !thick || thick->collision_free_at_t_star();
    // --hinge pin: the knuckles laid out as generate lays them (clear of each
    // other and of the plates at t* and over the thick interval), how many
    // hinges keep theirs, and every part judged as a solid against every other
    // and the plates, at the layout's configurations and half way between them.
    std::optional<PinLayout> pins;
    std::vector<PinCrossing> crossings;
    std::size_t hinges = 0, pin_checked = 0;
    if (thick && thick_fits && options->thickness.hinge == "pin") {
      const ThickPlates plates = thick_plates(loaded.design, *thick);
      pins = pin_layout(plates, pin_configurations(thick->t_star, thick->thick_lower, thick->thick_upper, pin_layout_samples));
      hinges = pins->margins.size();
      const std::vector<double> ts =
          pin_configurations(thick->t_star, thick->thick_lower, thick->thick_upper, 2 * pin_layout_samples - 1);
      crossings = pin_crossings(plates, *pins, ts);
      pin_checked = ts.size();
    }
    const bool pins_clear = crossings.empty();
    const std::optional<double> mm = millimetres_per_unit(loaded.design, options->thickness);
    // The rigid-panel model's mobility at t*: one internal mechanism, the motion
    // (informative; a design with a degenerate panel has no model: said so).
    std::optional<Mobility> mobile;
    std::string no_mobility;
    try {
      mobile = mobility(loaded.design, loaded.design.assembly.t_star());
    } catch (const InvalidInputError& e) {
      no_mobility = e.what();
    }
    if (options->json) {
      nlohmann::json j = report_json(report);
      j["geometry_passed"] = report.passed();
      j["passed"] = report.passed() && buildable && thick_fits && pins_clear;
      if (buildability) j["buildability"] = buildability->to_json();
      j["mobility"] = mobile ? mobile->to_json() : nlohmann::json{{"error", no_mobility}};
      if (thick) {
        j["thick"] = thick->to_json();
        j["thick_interval"] = j["thick"]["thick_interval"];
        if (mm) {  // --thickness-mm: the plates' figures in millimetres too
          j["thick"]["millimetres_per_unit"] = *mm;
          j["thick"]["thickness_mm"] = *mm * thick->thickness;
          j["thick"]["thickest_at_t_star_mm"] = thick->thickest ? nlohmann::json(*mm * *thick->thickest) : nlohmann::json(nullptr);
        }
        if (pins) {
          nlohmann::json crossing = nlohmann::json::array();
          for (const PinCrossing& c : crossings) {
            crossing.push_back({{"a", c.a}, {"b", c.b}, {"t", c.t}, {"depth", c.depth}});
          }
          j["thick"]["pin_hinges"] = {{"hinges", hinges},
                                      {"with_knuckles", hinges - pins->without_knuckles},
                                      {"without_knuckles", pins->without_knuckles},
                                      {"configurations_checked", pin_checked},
                                      {"crossings", crossing}};
        }
      }
      context.out << j.dump(2) << '\n';
    } else {
      const std::string& name = loaded.design.assembly.name();
      if (!report.passed()) {
        context.out << "FAIL: " << name << ": a geometric figure exceeds its tolerance\n";
      } else if (!buildability) {
        context.out << "PASS: " << name << ": the geometry holds (buildability not checked: --geometry-only)\n";
      } else if (buildable) {
        context.out << "PASS: " << name << ": the geometry holds and the design is buildable over its whole flexion interval\n";
      } else {
        context.out << "FAIL: " << name << ": the geometry holds, but the design is not buildable over its whole "
                       "flexion interval (below; --geometry-only checks the geometry alone)\n";
      }
      context.out << report;
      if (mobile) {
        context.out << *mobile;
      } else {
        context.out << "  mobility: not computed: " << no_mobility << '\n';
      }
      if (buildability) context.out << *buildability;
      if (thick) {
        if (!thick_fits) context.out << "FAIL: the plates " << format_human(thick->thickness) << " thick collide at t*\n";
        context.out << *thick;
        if (mm) {
          context.out << "  in millimetres (" << format_human(*mm) << " mm a model unit): plates " << format_human(*mm * thick->thickness)
                      << " mm thick";
          if (thick->thickest) context.out << ", the thickest that fit at t* " << format_human(*mm * *thick->thickest) << " mm";
          context.out << '\n';
        }
        if (pins) {
          context.out << "  pin hinges: " << hinges - pins->without_knuckles << " of " << hinges
                      << " hinges keep knuckles clear of each other and of the plates at t* and over the thick interval";
          if (pins->without_knuckles > 0) {
            context.out << "; " << pins->without_knuckles << " too short for that (generate leaves them without knuckles: "
                        << "tape or glue them, or thinner plates)";
          }
          context.out << '\n';
          if (pins_clear) {
            context.out << "  pin hinge parts: knuckles, leaves and pins clear of each other and of the plates at "
                        << pin_checked << " configurations (t* and " << pin_checked - 1 << " over the thick interval)\n";
          } else {
            const auto deepest = std::max_element(crossings.begin(), crossings.end(),
                                                  [](const PinCrossing& a, const PinCrossing& b) { return a.depth < b.depth; });
            context.out << "FAIL: pin hinge parts cut into each other or into a plate: " << crossings.size()
                        << (crossings.size() == 1 ? " crossing" : " crossings") << " at " << pin_checked
                        << " configurations; the deepest " << deepest->a << " into " << deepest->b << " at t = "
                        << format_human(deepest->t) << ", " << format_human(deepest->depth / thick->thickness)
                        << " of the plates' thickness deep\n";
          }
        }
      }
    }
    context.exit_code = report.passed() && buildable && thick_fits && pins_clear ? 0 : static_cast<int>(ExitCode::check_failed);
  });
}

}  // namespace phedra::cli
