// phedra sample PRESET (--t T | --fraction F | --count N)... [-o FILE]

#include "commands.h"
#include "motion_parameters.h"
#include "support.h"
#include "buildability_warning.h"
#include "phedra/errors.h"
#include "phedra/motion_document.h"
#include "phedra/thick_plates.h"

#include <algorithm>

#include <memory>

namespace phedra::cli {
namespace {

struct SampleOptions {
  std::string preset;
  MotionParameters parameters;
  std::string output;
  ThicknessOptions thickness;
};

/// The thick plates at every t: {thickness, side, hinge_gap, thick_interval,
/// panels, triangles (a plate's, into its own vertices), samples: [{t, vertices: [plate: [[x, y, z]]]}]}.
nlohmann::json plates_json(const Design& design, const BuildabilityReport& buildability, const ThickOptions& options,
                           const std::vector<double>& ts) {
  const ThickReport report = check_thickness(design, buildability, options);
  const ThickPlates plates = thick_plates(design, report);
  nlohmann::json j = {{"thickness", report.thickness}, {"side", to_string(report.side)}, {"hinge_gap", report.hinge_gap}};
  j["thick_interval"] = report.to_json()["thick_interval"];
  nlohmann::json panels = nlohmann::json::array(), triangles = nlohmann::json::array(), samples = nlohmann::json::array();
  const std::vector<Solid> first = plates.solids(plates.positions(ts.front()));
  for (std::size_t k = 0; k < plates.plates(); ++k) {
    panels.push_back(plates.panel(k));
    triangles.push_back(first[k].triangles);
  }
  for (const double t : ts) {
    nlohmann::json vertices = nlohmann::json::array();
    for (const Solid& solid : plates.solids(plates.positions(t))) {
      nlohmann::json plate = nlohmann::json::array();
      for (const Vec3& v : solid.vertices) {
        if (!v.allFinite()) throw Error(ExitCode::internal, "a plate vertex is not a finite number; nothing written");
        plate.push_back({v.x(), v.y(), v.z()});
      }
      vertices.push_back(std::move(plate));
    }
    samples.push_back({{"t", t}, {"vertices", std::move(vertices)}});
  }
  j["panels"] = std::move(panels);
  j["triangles"] = std::move(triangles);
  j["samples"] = std::move(samples);
  return j;
}

}  // namespace

void add_sample_command(CLI::App& app, Context& context) {
  auto options = std::make_shared<SampleOptions>();
  CLI::App* sub = app.add_subcommand(
      "sample", "Vertex positions at chosen motion parameters t, as JSON {labels, faces, samples: [{t, vertices}]}");
  add_preset_argument(sub, options->preset);
  options->parameters.add_options(sub);
  sub->add_option("-o,--output", options->output, "Output file (default: standard output)");
  add_thickness_options(sub, options->thickness,
                        "Also the thick plates of phedra check --thickness at every t: a \"plates\" object with each "
                        "plate's triangles and its vertices at each t (docs/formats.md)");
  sub->callback([options, sub, &context] {
    const Design design = load(context, options->preset);
    const std::vector<double> ts = options->parameters.values(sub, design.assembly);
    const BuildabilityReport buildability = assess_for_output(design);
    warn_unless_buildable(context, buildability, *std::min_element(ts.begin(), ts.end()),
                          *std::max_element(ts.begin(), ts.end()), "");
    MotionDocument document = motion_document(design);
    document.buildability = buildability.file_json();
    const std::optional<ThickOptions> thick = thick_options(design, options->thickness);
    if (!thick) {
      emit(motion_json(document, ts), options->output, options->preset, context.out);
      return;
    }
    nlohmann::json j = nlohmann::json::parse(motion_json(document, ts));
    j["plates"] = plates_json(design, buildability, *thick, ts);
    emit(j.dump() + "\n", options->output, options->preset, context.out);
  });
}

}  // namespace phedra::cli
