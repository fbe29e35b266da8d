// phedra sample PRESET (--t T | --fraction F | --count N)... [-o FILE]

#include "commands.h"
#include "motion_parameters.h"
#include "support.h"
#include "buildability_warning.h"
#include "phedra/motion_document.h"

#include <algorithm>

#include <memory>

namespace phedra::cli {
namespace {

struct SampleOptions {
  std::string preset;
  MotionParameters parameters;
  std::string output;
};

}  // namespace

void add_sample_command(CLI::App& app, Context& context) {
  auto options = std::make_shared<SampleOptions>();
  CLI::App* sub = app.add_subcommand(
      "sample", "Vertex positions at chosen motion parameters t, as JSON {labels, faces, samples: [{t, vertices}]}");
  add_preset_argument(sub, options->preset);
  options->parameters.add_options(sub);
  sub->add_option("-o,--output", options->output, "Output file (default: standard output)");
  sub->callback([options, sub, &context] {
    const Design design = load(context, options->preset);
    const std::vector<double> ts = options->parameters.values(sub, design.assembly);
    const BuildabilityReport buildability = assess_for_output(design);
    warn_unless_buildable(context, buildability, *std::min_element(ts.begin(), ts.end()),
                          *std::max_element(ts.begin(), ts.end()), "");
    MotionDocument document = motion_document(design);
    document.buildability = buildability.file_json();
    emit(motion_json(document, ts), options->output, options->preset, context.out);
  });
}

}  // namespace phedra::cli
