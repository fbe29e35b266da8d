// phedra check PRESET [--samples N] [--tolerance REL] [--closure-only] [--json]

#include "commands.h"
#include "phedra/assembly_check.h"
#include "phedra/errors.h"
#include "support.h"

#include <memory>
#include <ostream>

namespace phedra::cli {
namespace {

struct CheckCommandOptions {
  std::string preset;
  CheckOptions check;
  bool json = false;
};

}  // namespace

void add_check_command(CLI::App& app, Context& context) {
  auto options = std::make_shared<CheckCommandOptions>();
  CLI::App* sub = app.add_subcommand(
      "check", "Check planarity, isometry, tube closure and shared vertices over the whole flexion interval (dense "
               "samples, both limits and t*); exit 1 when a figure exceeds the tolerance");
  add_preset_argument(sub, options->preset);
  sub->add_option("--samples", options->check.samples, "Evenly spaced samples of [t_lambda, t_mu], limits included")
      ->check(CLI::Range(2, 10000000))
      ->capture_default_str();
  sub->add_option("--tolerance", options->check.relative_tolerance,
                  "Largest accepted figure, relative to the model size")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->add_flag_callback(
      "--closure-only", [options] { options->check.shape = false; },
      "The closure check alone: tube closure gaps, shared vertices and the reproduction at t*, without planarity "
      "and isometry of every panel (about three times faster on large arrays)");
  sub->add_flag("--json", options->json, "Print JSON instead of text");
  sub->callback([options, &context] {
    const Design design = load(context, options->preset);
    const AssemblyCheckReport report = check_assembly(design.assembly, options->check);
    if (options->json) {
      context.out << report.to_json().dump(2) << '\n';
    } else {
      context.out << report;
    }
    context.exit_code = report.passed() ? 0 : static_cast<int>(ExitCode::check_failed);
  });
}

}  // namespace phedra::cli
