#pragma once
// What the commands share: loading a preset and emitting a result.

#include "commands.h"
#include "phedra/design.h"
#include "phedra/panel_size.h"
#include "phedra/thick_plates.h"

#include <nlohmann/json.hpp>

#include <iosfwd>
#include <string>

namespace phedra::cli {

/// Registers the PRESET positional argument every design command takes.
void add_preset_argument(CLI::App* command, std::string& preset);

/// --max-growth and --max-panel-ratio: what counts as buildable by size (panel_size.h).
void add_size_bound_options(CLI::App* command, SizeBounds& bounds);

/// Thick plates: --thickness T (model units) or --thickness-mm MM on the cut
/// sheets' scale (--scale mm a model unit, or the model's size made --model-size
/// mm, as `phedra outlines`), and --plate-side.
struct ThicknessOptions {
  std::optional<double> model_units, mm, scale;
  double model_mm = 200.0;
  double hinge_gap = 0.0;  ///< in the thickness's units
  std::string side = "auto";
  std::string hinge = "none";  ///< none, gap (--hinge-gap, T/4 when not given), pin (hinge_pins.h)
  std::optional<std::string> printer;  ///< --printer: fdm, sla or a JSON file (PrinterProfile)
  bool print_in_place = false;         ///< generate --print-in-place: the printer's clearance between moving parts
};
void add_thickness_options(CLI::App* command, ThicknessOptions& options, const std::string& what);
/// The plate options asked for (none without --thickness or --thickness-mm).
std::optional<ThickOptions> thick_options(const Design& design, const ThicknessOptions& options);
/// --printer: refuses (InvalidInputError "--printer") pin hinge plates thinner than
/// the thinnest the printer makes parts for, saying the thickness and the scale
/// at which plates that thick fit the panels.
void refuse_unprintable(const Design& design, const ThicknessOptions& options, const ThickOptions& plates);
/// Millimetres a model unit with --thickness-mm (--scale, or the model's size
/// made --model-size mm: the cut sheets' scale); none with --thickness.
std::optional<double> millimetres_per_unit(const Design& design, const ThicknessOptions& options);

/// Loads and builds the design of a preset file; records the path in the context
/// so that errors name it.
Design load(Context& context, const std::string& path);

/// A design with the preset object it was built from (what field hints change).
struct LoadedDesign {
  nlohmann::json preset;
  Design design;
};
LoadedDesign load_with_preset(Context& context, const std::string& path);

/// Writes `content` to `path` (temporary file + rename), or to `out` when path
/// is empty or "-". Refuses to overwrite `input`.
void emit(const std::string& content, const std::string& path, const std::string& input, std::ostream& out);

/// The file of page (or bed) k of n: out.svg -> out-3.svg when there are several, `path` when n is 1.
std::string numbered(const std::string& path, std::size_t k, std::size_t n);

/// A field's value for people: numbers with 6 significant digits (or --full-precision), lists in brackets.
std::string human_value(const nlohmann::json& value);

/// `preset` as the text of a file, keys in the order the input file (at
/// `input_path`) has them (a reference case's preset object when the file is one).
std::string preset_text(const nlohmann::json& preset, const std::string& input_path);

}  // namespace phedra::cli
