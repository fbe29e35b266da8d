// phedra intersections PRESET [--samples N] [--json]

#include "commands.h"
#include "number_checks.h"
#include "phedra/errors.h"
#include "phedra/buildability.h"
#include "phedra/self_intersection.h"
#include "support.h"

#include <memory>
#include <ostream>

namespace phedra::cli {
namespace {

struct IntersectionsOptions {
  std::string preset;
  SelfIntersectionOptions sweep;
  SizeBounds bounds;
  bool json = false;
};

}  // namespace

void add_intersections_command(CLI::App& app, Context& context) {
  auto o = std::make_shared<IntersectionsOptions>();
  CLI::App* sub = app.add_subcommand(
      "intersections",
      "Find where the design intersects itself over its flexion interval: panels that penetrate each other and "
      "hinges that fold shut; print the intersection-free sub-interval around t* and the panels that end it, the "
      "invalid (bow-tie, degenerate, oversized, sliver) panels with their causes, and the buildable part of the interval; exit 1 when "
      "the configuration at t* itself intersects");
  add_preset_argument(sub, o->preset);
  sub->add_option("--samples", o->sweep.samples_per_side,
                  "Samples from t* to each flexion limit (crowding towards the limit); a collision is then "
                  "bisected to 1e-12 of the interval")
      ->check(whole_number_between(1, 1000000))
      ->capture_default_str();
  add_size_bound_options(sub, o->bounds);
  sub->add_flag("--json", o->json, "Print JSON instead of text");
  sub->callback([o, &context] {
    const LoadedDesign loaded = load_with_preset(context, o->preset);
    BuildabilityOptions options;
    options.sweep = o->sweep;
    options.bounds = o->bounds;
    const BuildabilityReport report = assess_buildability(loaded.design, &loaded.preset, options);
    if (o->json) {
      nlohmann::json j = report.motion.to_json();
      j["buildability"] = report.to_json();
      context.out << j.dump(2) << '\n';
    } else {
      context.out << report.motion << report;
    }
    context.exit_code = report.motion.at_t_star ? static_cast<int>(ExitCode::check_failed) : 0;
  });
}

}  // namespace phedra::cli
