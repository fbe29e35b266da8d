#include "support.h"
#include "phedra/buildability.h"
#include "phedra/errors.h"
#include "number_checks.h"

#include "phedra/hinge_pins.h"

#include "phedra/files.h"
#include "phedra/number_format.h"
#include "phedra/preset.h"
#include "phedra/design_preset.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <ostream>

namespace phedra::cli {

void add_preset_argument(CLI::App* command, std::string& preset) {
  command->add_option("preset", preset, "Preset file (JSON, docs/presets.md)")->required();
}

void add_size_bound_options(CLI::App* command, SizeBounds& bounds) {
  command->add_option("--max-growth", bounds.max_growth,
                      "Buildability: the design's bounding-box diagonal may grow to this many times its size at t* "
                      "over the buildable interval, no further (0: no bound)")
      ->check(zero_or_at_least(1.0))
      ->capture_default_str();
  command->add_option("--max-panel-ratio", bounds.max_edge_ratio,
                      "Buildability: a panel whose longest edge is more than this many times the median panel's is "
                      "oversized (0: no bound); a panel thinner than " + format_significant(bounds.min_aspect, 3) +
                      " of its length is a sliver")
      ->check(zero_or_at_least(1.0))
      ->capture_default_str();
}

void add_thickness_options(CLI::App* command, ThicknessOptions& o, const std::string& what) {
  CLI::Option* model = command->add_option("--thickness", o.model_units, what + " (model units)")->check(positive_number());
  CLI::Option* mm = command->add_option("--thickness-mm", o.mm,
                                        "The same in millimetres on the cut sheets' scale (--scale, or --model-size as "
                                        "phedra outlines); generate's solids are then in millimetres too")
                        ->check(positive_number())
                        ->excludes(model);
  CLI::Option* scale = command->add_option("--scale", o.scale, "With --thickness-mm: millimetres a model unit")
                           ->check(positive_number())
                           ->needs(mm);
  command->add_option("--model-size", o.model_mm,
                      "With --thickness-mm and no --scale: the model's size in mm (as phedra outlines)")
      ->check(positive_number())
      ->needs(mm)
      ->excludes(scale)
      ->capture_default_str();
  command->add_option("--hinge-gap", o.hinge_gap,
                      "With a thickness: a gap this wide at every hinge (in the thickness's units: model units, or mm "
                      "with --thickness-mm), each plate's hinge sides moved back by half of it, for a tape, fabric or "
                      "printed-film hinge across it")
      ->check(non_negative_number())
      ->capture_default_str();
  command->add_option("--hinge", o.hinge,
                      "With a thickness: how the plates are hinged: none (plates meet at the hinge lines), gap (a gap at "
                      "every hinge: --hinge-gap, or a quarter of the thickness), or pin (knuckles on every hinge line, "
                      "alternating between its plates, a pin through them; the plates cut back to clear them: solids "
                      "from generate; check fails, exit 1, when two parts or a part and a plate cross over the thick "
                      "interval; docs/design.md)")
      ->check(CLI::IsMember({"none", "gap", "pin"}))
      ->capture_default_str();
  command->add_option("--printer", o.printer,
                      "With --hinge pin and --thickness-mm: the printer the hinge parts are made on: fdm (pins 2 mm, "
                      "clearance 0.3 mm, gaps 0.4 mm, walls 0.8 mm), sla (1, 0.15, 0.2, 0.3 mm) or a JSON file of "
                      "nozzle_mm, smallest_feature_mm, clearance_mm, pin_mm, gap_mm; plates thinner than the thinnest "
                      "whose parts it makes are refused, with the scale at which plates that thick fit");
  command->add_option("--plate-side", o.side,
                      "With a thickness: the side of the panels the plates lie on: front (the side the panel normals "
                      "of the exports point to), back, or auto (the side with the wider thick interval)")
      ->check(CLI::IsMember({"auto", "front", "back"}))
      ->capture_default_str();
}

std::optional<double> millimetres_per_unit(const Design& design, const ThicknessOptions& o) {
  if (!o.mm) return std::nullopt;
  return o.scale ? *o.scale : o.model_mm / bounded_model_size(design);
}

namespace {

/// --printer NAME|FILE: the built-in profiles, or one read from a JSON file.
PrinterProfile printer_profile(const std::string& name) {
  if (name == "fdm") return fdm_printer();
  if (name == "sla") return sla_printer();
  if (!std::filesystem::exists(name)) {
    throw InvalidInputError("--printer", "\"" + name + "\" is neither fdm, sla nor a file of a printer's sizes");
  }
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(read_text_file(name));
  } catch (const nlohmann::json::parse_error& e) {
    throw InvalidInputError("--printer", name + ": not JSON (" + std::string(e.what()) + ")");
  }
  if (!j.is_object()) throw InvalidInputError("--printer", name + ": expected an object of sizes in mm");
  PrinterProfile p = fdm_printer();
  p.name = name;
  const std::pair<const char*, double*> fields[] = {{"nozzle_mm", &p.nozzle_mm},
                                                    {"smallest_feature_mm", &p.smallest_feature_mm},
                                                    {"clearance_mm", &p.clearance_mm},
                                                    {"pin_mm", &p.pin_mm},
                                                    {"gap_mm", &p.gap_mm}};
  for (auto item = j.begin(); item != j.end(); ++item) {
    const std::string key = item.key();
    const nlohmann::json& value = item.value();
    const auto field = std::find_if(std::begin(fields), std::end(fields), [&](const auto& f) { return key == f.first; });
    if (field == std::end(fields)) {
      throw InvalidInputError("--printer", name + ": unknown key \"" + key +
                                               "\" (nozzle_mm, smallest_feature_mm, clearance_mm, pin_mm, gap_mm)");
    }
    if (!value.is_number() || !(value.get<double>() > 0.0) || !(value.get<double>() <= 100.0)) {
      throw InvalidInputError("--printer", name + ": " + key + " must be a number of millimetres in (0, 100]");
    }
    *field->second = value.get<double>();
  }
  return p;
}

}  // namespace

void refuse_unprintable(const Design& design, const ThicknessOptions& o, const ThickOptions& plates) {
  if (o.hinge != "pin") throw InvalidInputError("--printer", "a printer sizes pin hinge parts: add --hinge pin");
  if (!o.mm) throw InvalidInputError("--printer", "a printer's sizes are millimetres: give --thickness-mm");
  const PrinterProfile printer = printer_profile(*o.printer);
  std::string binding;
  const double thinnest = thinnest_printable_mm(printer, &binding, o.print_in_place);
  if (*o.mm >= thinnest * (1.0 - 1e-12)) return;
  // The scale at which plates that thick fit: pin hinges' gap grows with the
  // plates, so the thickest that fit at t* is the same in model units at every scale.
  ThickOptions probe = plates;
  probe.thickness = 1e-3 * design.assembly.model_size();
  probe.hinge_gap = probe.hinge_gap_at(probe.thickness);
  probe.find_thickest = true;
  const ThickReport r = check_thickness(design, assess_buildability(design), probe);
  const double mm_per_unit = *millimetres_per_unit(design, o);
  std::string where;
  if (r.thickest && *r.thickest > 0.0) {
    // The thickest is found to 1 %: 2 % more, rounded up to 3 significant digits.
    const double need = 1.02 * thinnest / *r.thickest, step = std::pow(10.0, std::floor(std::log10(need)) - 2.0);
    const double scale = std::ceil(need / step) * step;
    where = scale <= mm_per_unit ? " (they fit the panels at this scale)"
                                 : " on a scale of at least " + format_human(scale) + " mm a model unit (--scale; " +
                                       format_human(mm_per_unit) + " now), where plates that thick fit the panels";
  }
  throw InvalidInputError("--printer", printer.name + " makes pin hinge parts" + (o.print_in_place ? " printed in place" : "") +
                                           " for plates at least " + format_human(thinnest) +
                                           " mm thick (" + binding + "), not " + format_human(*o.mm) +
                                           " mm: --thickness-mm " + format_human(thinnest) + where +
                                           ", or --hinge gap for a tape or film hinge");
}

std::optional<ThickOptions> thick_options(const Design& design, const ThicknessOptions& o) {
  if (!o.model_units && !o.mm) return std::nullopt;
  ThickOptions out;
  out.side = plate_side_from_string(o.side);
  const double unit = o.model_units ? 1.0 : 1.0 / *millimetres_per_unit(design, o);
  out.thickness = (o.model_units ? *o.model_units : *o.mm) * unit;
  if (const double resolved = 1e-6 * design.assembly.model_size(); o.mm && out.thickness < resolved) {
    // In the user's unit: the plates' own check says it in model units, for --thickness.
    throw InvalidInputError("--thickness-mm", "plates " + format_human(*o.mm) + " mm thick are below what the model "
                                              "resolves (1e-6 of its size, " + format_human(resolved / unit) +
                                              " mm on this scale): such plates are the panels themselves");
  }
  // The gap follows the plates when a pin hinge or a default gap sets it (and the
  // thickest plates are searched so: each thickness with its own gap).
  if (o.mm) out.millimetres_per_unit = 1.0 / unit;
  out.hinge_gap_fixed = o.hinge_gap * unit;
  if (o.hinge == "gap" && o.hinge_gap == 0.0) out.hinge_gap_per_thickness = 0.25;
  if (o.hinge == "pin") out.hinge_gap_per_thickness = pin_hinge_gap(1.0);  // linear in the thickness
  out.hinge_gap = out.hinge_gap_per_thickness > 0.0 ? out.hinge_gap_at(out.thickness) : out.hinge_gap_fixed;
  if (o.printer) refuse_unprintable(design, o, out);
  return out;
}

Design load(Context& context, const std::string& path) {
  context.preset = path;
  return load_design(path);
}

LoadedDesign load_with_preset(Context& context, const std::string& path) {
  context.preset = path;
  const nlohmann::json document = parse_json_text(read_text_file(path));
  Design design = design_from_json(document);
  return {preset_object(document), std::move(design)};
}

void emit(const std::string& content, const std::string& path, const std::string& input, std::ostream& out) {
  if (path.empty() || path == "-") {
    out << content;
    return;
  }
  refuse_overwriting_input(path, input);
  write_file_atomically(path, content);
}

std::string numbered(const std::string& path, std::size_t k, std::size_t n) {
  if (n == 1) return path;
  const std::filesystem::path p(path);
  return (p.parent_path() / (p.stem().string() + "-" + std::to_string(k + 1) + p.extension().string())).string();
}

/// A field's value for people: numbers with 6 significant digits (or --full-precision), lists in brackets.
std::string human_value(const nlohmann::json& value) {
  if (value.is_number()) return format_human(value.get<double>());
  if (!value.is_array()) return value.dump();
  std::string out = "[";
  for (std::size_t k = 0; k < value.size(); ++k) out += (k ? ", " : "") + human_value(value[k]);
  return out + "]";
}

std::string preset_text(const nlohmann::json& preset, const std::string& input_path) {
  nlohmann::ordered_json document = nlohmann::ordered_json::parse(read_text_file(input_path));
  if (document.is_object() && document.contains("preset") && !document.contains("trajectory")) {
    document = nlohmann::ordered_json(document["preset"]);
  }
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  if (document.is_object()) {
    for (const auto& [key, value] : document.items()) {
      if (preset.contains(key)) out[key] = nlohmann::ordered_json::parse(preset[key].dump());
    }
  }
  for (const auto& [key, value] : preset.items()) {
    if (!out.contains(key)) out[key] = nlohmann::ordered_json::parse(value.dump());
  }
  return out.dump(2) + "\n";
}

}  // namespace phedra::cli
