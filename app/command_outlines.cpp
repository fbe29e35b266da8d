// phedra outlines PRESET -o FILE.pdf|.svg|.png|.dxf [--pieces MODE] [--page SIZE] [--scale S] [--no-tabs]

#include "buildability_warning.h"
#include "number_checks.h"
#include "commands.h"
#include "phedra/number_format.h"
#include "phedra/cut_sheets.h"
#include "phedra/errors.h"
#include "support.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <ostream>

namespace phedra::cli {
namespace {

struct OutlinesCommandOptions {
  std::string preset;
  std::string output;
  std::string pieces = "strips";
  std::string page = "a4";
  double scale = 0.0;  ///< 0: from --model-size
  std::optional<double> thickness_mm;
  double kerf_mm = 0.0;
  std::string plate_side = "auto";
  CutSheetOptions sheets;
};

/// The summary's numbers: 6 significant digits, or round-trip ones with --full-precision.
std::string six(double x) { return format_human(x); }

}  // namespace

void add_outlines_command(CLI::App& app, Context& context) {
  auto o = std::make_shared<OutlinesCommandOptions>();
  CLI::App* sub = app.add_subcommand(
      "outlines",
      "Cut sheets: the panels unfolded into connected pieces (by default one per strip) with mountain and valley "
      "fold lines, glue tabs and matching seam labels (S<k>), each panel labelled with its number in the exports "
      "(P<k>), laid out in assembly order on pages with a title, legend and scale bar. PDF (every page), SVG or "
      "PNG (one file per page: out-1.svg, out-2.svg, ... when there are several) or DXF (pages side by side; "
      "layers CUT, MOUNTAIN, VALLEY, TAB_FOLD, LABELS)");
  add_preset_argument(sub, o->preset);
  sub->add_option("-o,--output", o->output, "Output file: .pdf, .svg, .png or .dxf")->required();
  CLI::Option* pieces = sub->add_option("--pieces", o->pieces,
                  "strips (the panels between two profiles), columns (along the trajectory), cells (each member of "
                  "an array on its own, walls glued face to face) or panels (one by one)")
      ->capture_default_str();
  sub->add_option("--page", o->page, "Page size: a4, letter, a3 or WxH in mm (e.g. 300x200)")->capture_default_str();
  CLI::Option* scale = sub->add_option("--scale", o->scale, "Millimetres on the sheet per model unit (default: the model size becomes "
                                       "--model-size mm)")
                           ->check(positive_number());
  sub->add_option("--model-size", o->sheets.model_mm, "Without --scale: the model's size (bounding-box diagonal at "
                                                      "t*) on paper, in mm")
      ->check(positive_number())
      ->capture_default_str();
  sub->add_flag("!--no-tabs", o->sheets.tabs, "No glue tabs on the seams");
  sub->add_flag("--tabs", o->sheets.tabs, "Glue tabs on the seams (the default)");
  sub->add_option("--tab-depth", o->sheets.tab_depth, "Tab depth relative to its seam's length, in (0, 0.5); at "
                                                      "most 6 mm")
      ->check(number_inside(0.0, 0.5))
      ->capture_default_str();
  sub->add_option("--thickness-mm", o->thickness_mm,
                   "Thick plates cut from sheet material this thick (mm on the sheets' scale): one piece a plate, "
                   "its cut outline inside the bevelled plate of phedra check --thickness, hinge lines, pieces "
                   "numbered in assembly order, an assembly page, the material used (docs/cli.md)")
      ->check(positive_number());
  sub->add_option("--kerf", o->kerf_mm, "With --thickness-mm: the width (mm) the laser or saw burns away; cut paths "
                                        "run half of it outside each piece")
      ->check(non_negative_number())
      ->capture_default_str();
  sub->add_option("--plate-side", o->plate_side, "With --thickness-mm: front, back or auto (as phedra check)")
      ->check(CLI::IsMember({"auto", "front", "back"}))
      ->capture_default_str();
  sub->callback([o, scale, pieces, &context] {
    const std::string ext = std::filesystem::path(o->output).extension().string();
    if (ext != ".svg" && ext != ".dxf" && ext != ".pdf" && ext != ".png") {
      throw InvalidInputError("output", "unknown format \"" + ext + "\" (use .pdf, .svg, .png or .dxf)");
    }
    o->sheets.mode = piece_mode_from_string(o->pieces);
    o->sheets.page = page_size_from_string(o->page);
    if (scale->count() > 0) o->sheets.scale = o->scale;
    if (!(o->sheets.model_mm > 0.0)) throw InvalidInputError("--model-size", "must be a positive number of mm");
    if (o->thickness_mm && pieces->count() > 0 && o->sheets.mode != PieceMode::panels) {
      throw InvalidInputError("--pieces", "plates cut from sheet material are one piece each (--thickness-mm): "
                                          "drop --pieces or use panels");
    }
    if (o->thickness_mm) {
      o->sheets.plates = PlateCut{*o->thickness_mm, o->kerf_mm, plate_side_from_string(o->plate_side)};
    } else if (o->kerf_mm != 0.0) {
      throw InvalidInputError("--kerf", "a kerf is for plates cut from sheet material: give --thickness-mm too");
    }
    const Design design = load(context, o->preset);
    const CutSheets sheets = cut_sheets(design, o->sheets);
    // Everything is drawn before anything is written.
    std::vector<std::pair<std::string, std::string>> files;
    if (ext == ".pdf") {
      files.push_back({o->output, cut_sheets_pdf(sheets)});
    } else if (ext == ".dxf") {
      files.push_back({o->output, cut_sheets_dxf(sheets)});
    } else {
      for (std::size_t k = 0; k < sheets.pages.size(); ++k) {
        files.push_back({numbered(o->output, k, sheets.pages.size()),
                         ext == ".svg" ? sheet_page_svg(sheets, k) : page_png(sheets.pages[k], sheets.page)});
      }
    }
    for (const auto& [path, content] : files) emit(content, path, o->preset, context.out);
    const BuildabilityReport buildability = assess_for_output(design);
    std::size_t panels = 0;
    for (const Piece& piece : sheets.pieces) panels += piece.panels.size();
    context.out << "wrote " << (files.size() == 1 ? o->output : files.front().first + " ... " + files.back().first)
                << ": " << sheets.pages.size() << (sheets.pages.size() == 1 ? " page" : " pages") << " of "
                << six(sheets.page.x()) << " x " << six(sheets.page.y()) << " mm, " << sheets.pieces.size()
                << " pieces (" << (sheets.thick ? std::string("plates") : to_string(sheets.mode)) << ") of " << panels
                << " panels, "
                << (sheets.thick ? std::to_string(sheets.seams) + " hinges"
                                 : std::to_string(sheets.folds) + " fold lines, " + std::to_string(sheets.seams) +
                                       " seams to glue (" + std::to_string(sheets.tabs) + " tabs)")
                << ", scale " << six(sheets.scale) << " mm per model unit\n";
    if (!sheets.thick) {
      context.out << "assembly on pages " << sheets.piece_pages + 1 << "-" << sheets.pages.size()
                  << " (the order, then views of it)\n";
    }
    if (sheets.thick) {
      const ThickReport& r = *sheets.thick;
      context.out << "plates " << six(sheets.thickness_mm) << " mm thick (" << six(r.thickness) << " model units) on the "
                  << to_string(r.side) << " side, kerf " << six(sheets.kerf_mm) << " mm; assembly on pages "
                  << sheets.piece_pages + 1 << "-" << sheets.pages.size() << " (the order, then views of it); material: " << sheets.piece_pages << " sheet"
                  << (sheets.piece_pages == 1 ? "" : "s") << " of " << six(sheets.page.x()) << " x " << six(sheets.page.y())
                  << " mm, " << six(sheets.cut_area_mm2 / 100.0) << " cm^2 of pieces ("
                  << six(100.0 * sheets.material_used()) << " % of the sheets)\n";
      if (r.at_t_star) {
        context.err << "phedra: warning: the plates collide at t* (phedra check --thickness " << six(r.thickness)
                    << " names them)\n";
      } else {
        context.out << "thick interval [" << six(r.thick_lower) << ", " << six(r.thick_upper) << "] of [" << six(r.t_lambda)
                    << ", " << six(r.t_mu) << "]\n";
      }
      // Plates that hardly fold: said in words (as on the first page), with the thickness that would.
      const std::vector<std::string> words = plates_fold_words(sheets);
      for (std::size_t k = 0; k < words.size(); ++k) context.err << (k ? "; " : "phedra: warning: ") << words[k];
      if (!words.empty()) context.err << '\n';
    }
    if (sheets.called_out > 0) {
      context.out << "note: " << sheets.called_out << " label" << (sheets.called_out == 1 ? " is" : "s are")
                  << " called out beside " << (sheets.called_out == 1 ? "its piece" : "their pieces")
                  << " with a leader (no room for 2 mm inside the panel); a larger --scale or --model-size keeps them inside\n";
    }
    if (sheets.untabbed_seams > 0) {
      context.out << "note: " << sheets.untabbed_seams << " seams have no room for a tab on either side: "
                  << "glue them with tape\n";
    }
    if (sheets.smallest_label < readable_label_mm) {
      context.err << "phedra: warning: the smallest label is " << six(sheets.smallest_label)
                  << " mm high (panels too small for it); a larger --scale or --model-size makes every label "
                  << "larger\n";
    }
    // Oversized panels and slivers are left off the sheets; bow-ties and degenerate ones are on them, red.
    std::vector<std::size_t> red;
    for (const PanelDiagnosis& d : buildability.invalid) {
      if (d.shape != PanelShape::oversized && d.shape != PanelShape::sliver) red.push_back(d.panel);
    }
    auto list = [](const std::vector<std::size_t>& numbers) {
      std::string text;
      for (std::size_t k = 0; k < numbers.size(); ++k) text += (k ? ", " : "") + std::to_string(numbers[k]);
      return text;
    };
    if (!sheets.left_out.empty()) {
      context.err << "phedra: warning: panel" << (sheets.left_out.size() == 1 ? " " : "s ") << list(sheets.left_out)
                  << " left off the sheets: oversized or slivers, nothing one can cut (the scale is set by the other "
                  << "panels); `phedra check " << o->preset << "` names the cause of each and the field to change\n";
    }
    if (!red.empty()) {
      context.err << "phedra: warning: " << red.size() << " of " << buildability.panels
                  << " panels cannot be cut as one plate (filled red on the sheets): panels " << list(red) << "; `phedra check "
                  << o->preset << "` names the cause of each and the field to change\n";
    }
    context.out << "buildability: " << buildability.summary() << '\n';
  });
}

}  // namespace phedra::cli
