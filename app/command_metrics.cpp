// phedra metrics PRESET [--samples N] [-o FILE.csv|.json|.svg]... [--json]

#include "commands.h"
#include "number_checks.h"
#include "phedra/errors.h"
#include "phedra/metamaterial_metrics.h"
#include "support.h"
#include "buildability_warning.h"

#include <filesystem>
#include <memory>
#include <ostream>

namespace phedra::cli {
namespace {

struct MetricsCommandOptions {
  std::string preset;
  MetricsOptions metrics;
  std::vector<std::string> outputs;
  bool json = false;
};

}  // namespace

void add_metrics_command(CLI::App& app, Context& context) {
  auto o = std::make_shared<MetricsCommandOptions>();
  CLI::App* sub = app.add_subcommand(
      "metrics", "Metamaterial figures against t: lengths along three axes fixed at t* (homogenized stretch), enclosed volume of every "
                 "tube and of the array, deployment ratios and effective Poisson's ratios; writes CSV, JSON and an "
                 "SVG plot");
  add_preset_argument(sub, o->preset);
  sub->add_option("--samples", o->metrics.samples, "Evenly spread over [t_lambda, t_mu], limits included (t* is added)")
      ->check(whole_number_between(2, 1000000))
      ->capture_default_str();
  sub->add_option_function<std::string>(
         "--axes", [o](const std::string& name) { o->metrics.axes = parse_metrics_axes(name); },
         "The three axes, fixed at t*: structural (1 along the trajectory, 2 across it where the design spreads most, "
         "3 normal to both) or xyz (the preset's frame)")
      ->default_str("structural");
  sub->add_option("-o,--output", o->outputs, "Write the figures: .csv (one row per t), .json or .svg (plots); repeatable")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  sub->add_flag("--json", o->json, "Print the JSON on standard output instead of the summary");
  sub->callback([o, &context] {
    // Formats first: a bad extension must not leave other files half done.
    for (const std::string& path : o->outputs) {
      const std::string ext = std::filesystem::path(path).extension().string();
      if (ext != ".csv" && ext != ".json" && ext != ".svg") {
        throw InvalidInputError("output", "unknown format \"" + ext + "\" for " + path + " (use .csv, .json or .svg)");
      }
    }
    const Design design = load(context, o->preset);
    MetricsReport report = metamaterial_metrics(design, o->metrics);
    const BuildabilityReport buildability = assess_for_output(design);
    report.buildability_known = true;
    report.buildable = buildability.interval();
    nlohmann::json document = report.to_json();
    document["buildability"] = buildability.file_json();
    for (const std::string& path : o->outputs) {
      const std::string ext = std::filesystem::path(path).extension().string();
      const std::string text = ext == ".csv" ? report.to_csv() : ext == ".svg" ? report.to_svg() : document.dump(2) + "\n";
      emit(text, path, o->preset, context.out);
    }
    if (o->json) {
      context.out << document.dump(2) << '\n';
    } else {
      context.out << report;
      context.out << "buildability: " << buildability.summary() << '\n';
      for (const std::string& path : o->outputs) context.out << "wrote " << path << '\n';
    }
  });
}

}  // namespace phedra::cli
