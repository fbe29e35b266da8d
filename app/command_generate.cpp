// phedra generate PRESET -o FILE [--count N | --t T | --fraction F ...]

#include "commands.h"
#include "motion_parameters.h"
#include "phedra/number_format.h"
#include "support.h"

#include <memory>
#include <ostream>

namespace phedra::cli {
namespace {

struct GenerateOptions {
  std::string preset;
  MotionParameters parameters;
  std::string output;
};

}  // namespace

void add_generate_command(CLI::App& app, Context& context) {
  auto options = std::make_shared<GenerateOptions>();
  CLI::App* sub = app.add_subcommand(
      "generate", "Build the preset's P-hedron, tube or tube array and write its mesh and folding motion over the "
                  "whole flexion interval (JSON, docs/formats.md)");
  sub->add_option("preset", options->preset, "Preset file (JSON, docs/presets.md)")->required();
  sub->add_option("-o,--output", options->output, "Output file (.json)")->required();
  options->parameters.add_options(sub, 41);
  sub->callback([options, sub, &context] {
    const Design design = load(context, options->preset);
    const std::vector<double> ts = options->parameters.values(sub, design.assembly);
    const MotionDocument document = motion_document(design);
    emit(motion_json(document, ts), options->output, options->preset, context.out);
    context.out << "wrote " << options->output << ": " << design.kind << " \"" << design.assembly.name() << "\", "
                << document.labels.size() << " vertices, " << document.faces.size() << " faces, " << ts.size()
                << " configurations over [" << format_number(ts.front()) << ", " << format_number(ts.back()) << "]\n";
  });
}

}  // namespace phedra::cli
