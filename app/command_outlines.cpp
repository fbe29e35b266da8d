// phedra outlines PRESET -o FILE.svg|.dxf [--tabs] [--tab-depth R] [--spacing R]

#include "commands.h"
#include "phedra/errors.h"
#include "phedra/flat_outlines.h"
#include "phedra/number_format.h"
#include "support.h"
#include "buildability_warning.h"

#include <filesystem>
#include <memory>
#include <ostream>

namespace phedra::cli {
namespace {

struct OutlinesCommandOptions {
  std::string preset;
  std::string output;
  OutlineOptions outline;
};

}  // namespace

void add_outlines_command(CLI::App& app, Context& context) {
  auto o = std::make_shared<OutlinesCommandOptions>();
  CLI::App* sub = app.add_subcommand(
      "outlines", "Fabrication: the flat outline of every panel on one sheet, labelled with its panel id (P<k>, as in "
                  "the exports) and the hinge id of each edge (H<k>: join the edges with the same label), optional "
                  "glue tabs; SVG (in mm, --scale per model unit) or DXF (layers CUT, FOLD, LABELS)");
  add_preset_argument(sub, o->preset);
  sub->add_option("-o,--output", o->output, "Output file: .svg or .dxf")->required();
  sub->add_flag("--tabs", o->outline.tabs, "A glue tab on one side of every hinge (on the panel with the lower id)");
  sub->add_option("--tab-depth", o->outline.tab_depth, "Tab depth relative to its hinge's length, in (0, 0.5)")
      ->capture_default_str();
  sub->add_option("--spacing", o->outline.spacing, "Gap between panels relative to the model size")
      ->capture_default_str();
  sub->add_option("--scale", o->outline.scale, "Millimetres on the sheet per model unit")->capture_default_str();
  sub->callback([o, &context] {
    const std::string ext = std::filesystem::path(o->output).extension().string();
    if (ext != ".svg" && ext != ".dxf") {
      throw InvalidInputError("output", "unknown format \"" + ext + "\" (use .svg or .dxf)");
    }
    const Design design = load(context, o->preset);
    const OutlineSheet sheet = flat_outlines(design, o->outline);
    emit(ext == ".svg" ? outlines_svg(sheet) : outlines_dxf(sheet), o->output, o->preset, context.out);
    const BuildabilityReport buildability = assess_for_output(design);
    context.out << "wrote " << o->output << ": " << sheet.panels.size() << " panel outlines, " << sheet.hinges
                << " hinges" << (o->outline.tabs ? " with a tab each" : "") << ", sheet " << format_number(sheet.width)
                << " x " << format_number(sheet.height) << " mm\n";
    if (!buildability.panels_simple()) {
      context.err << "phedra: warning: " << buildability.invalid.size() << " of " << buildability.panels
                  << " panels cannot be cut as one plate (outlined in red on the sheet): panels "
                  << buildability.invalid_list() << "; `phedra check " << o->preset
                  << "` names the cause of each and the field to change\n";
    }
    context.out << "buildability: " << buildability.summary() << '\n';
  });
}

}  // namespace phedra::cli
