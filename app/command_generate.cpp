// phedra generate PRESET -o FILE(.glb|.gltf|.json) [options]

#include "commands.h"
#include "number_checks.h"
#include "motion_parameters.h"
#include "phedra/errors.h"
#include "phedra/fold_export.h"
#include "phedra/gltf_export.h"
#include "phedra/mesh_export.h"
#include "phedra/number_format.h"
#include "phedra/self_intersection.h"
#include "phedra/solid_export.h"
#include "phedra/print_beds.h"
#include "phedra/thick_plates.h"
#include "phedra/hinge_pins.h"
#include "buildability_warning.h"
#include "progress.h"
#include "support.h"
#include "phedra/motion_document.h"

#include <algorithm>
#include <limits>
#include <filesystem>
#include <memory>
#include <numeric>
#include <ostream>

namespace phedra::cli {
namespace {

struct GenerateOptions {
  std::string preset;
  std::string output;
  MotionParameters parameters;
  double seconds = 4.0;
  bool ping_pong = false;
  double ease = 1.0 / 16.0;
  std::optional<double> static_t;
  double hinge_tolerance = 1e-3;
  bool quiet = false;
  bool morph = false;  ///< --morph: the default, said explicitly
  bool nodes = false;  ///< --nodes: a rigid node per panel
  bool cycle = false;
  bool no_self_intersection = false;
  std::optional<std::size_t> intersection_samples;  ///< default: sweep_samples_for(panels)
  ThicknessOptions thickness;
  std::string layout = "assembled";  ///< --layout: assembled (at t) or print (laid flat on beds)
  std::string bed = "200x200";       ///< --bed, mm
};

/// --no-self-intersection: the intersection-free sub-interval around t*.
std::optional<std::pair<double, double>> free_range(Context& context, const SelfIntersectionReport& report,
                                                    const GenerateOptions& o) {
  if (!o.no_self_intersection) return std::nullopt;
  const std::pair<double, double> range = intersection_free_interval(report);
  if (!(range.second > range.first)) {
    throw InvalidInputError("--no-self-intersection", "the intersection-free interval is the single configuration t = " +
                                                          format_human(range.first));
  }
  context.out << "intersection-free interval [" << format_human(range.first) << ", " << format_human(range.second)
              << "] of the flexion interval [" << format_human(report.t_lambda) << ", "
              << format_human(report.t_mu) << "]\n";
  return range;
}

enum class Format { glb, gltf, json, fold, obj, ply, stl, three_mf };

/// A static t (--at) must lie in the intersection-free interval when one is asked for.
void check_in_range(const std::optional<double>& t, const std::optional<std::pair<double, double>>& range) {
  if (!t || !range || (*t >= range->first && *t <= range->second)) return;
  throw InvalidInputError("--at", "t = " + format_number(*t) + " is outside the intersection-free interval [" +
                                      format_number(range->first) + ", " + format_number(range->second) + "]");
}

Format format_of(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".glb") return Format::glb;
  if (ext == ".gltf") return Format::gltf;
  if (ext == ".json") return Format::json;
  if (ext == ".fold") return Format::fold;
  if (ext == ".obj") return Format::obj;
  if (ext == ".ply") return Format::ply;
  if (ext == ".stl") return Format::stl;
  if (ext == ".3mf") return Format::three_mf;
  throw InvalidInputError("output", "unknown format \"" + ext + "\" (use .glb, .gltf, .fold, .obj, .ply, .json, or with "
                                    "--thickness .stl, .3mf, .obj)");
}

void write_gltf(Context& context, const Design& design, const GenerateOptions& o, bool binary,
                const std::optional<std::pair<double, double>>& range, const BuildabilityReport& buildability,
                const nlohmann::json& preset) {
  GltfOptions options;
  options.preset_text = preset.dump();
  options.buildability = buildability.file_json();
  options.range = range;
  options.binary = binary;
  options.seconds = o.seconds;
  options.ping_pong = o.ping_pong;
  options.ease = o.ease;
  options.static_t = o.static_t;
  options.morph = !o.nodes;
  options.cycle = o.cycle;
  options.keyframes.relative_tolerance = o.hinge_tolerance;
  Progress progress(context.err, "keyframes", !o.quiet);
  options.progress = [&](double fraction, std::size_t count) {
    progress.update(fraction, std::to_string(count) + " keyframes");
  };
  if (o.static_t && !design.assembly.flexion_interval().contains(*o.static_t)) {
    const FlexionInterval& f = design.assembly.flexion_interval();
    throw OutOfIntervalError(*o.static_t, f.lower.t, f.upper.t);
  }
  check_in_range(o.static_t, range);
  GltfReport report;
  const std::string bytes = gltf_bytes(design, options, &report);
  progress.finish();
  emit(bytes, o.output, o.preset, context.out);
  context.out << "wrote " << o.output << ": " << design.kind << " \"" << design.assembly.name() << "\", "
              << report.panels
              << (o.nodes ? " panels (one node each, hinge tree " + std::to_string(report.tree_depth) + " levels deep)"
                          : std::string(" panels (one mesh, morph targets)"));
  if (o.static_t) {
    context.out << ", static at t = " << format_human(*o.static_t) << '\n';
    return;
  }
  const char* back = o.ping_pong ? ", and back" : "";
  if (o.cycle) {
    const PHedron::ConfigurationCycle c = design.assembly.base().configuration_cycle();
    context.out << ", " << report.keyframes << " keyframes along the configuration curve (" << c.passes.size()
                << " passes through the flexion limits, " << (c.closed ? "closed" : "open: " + c.stop) << "), "
                << format_human(o.seconds) << " s a full traversal of the interval" << back << '\n';
  } else {
    const FlexionInterval& f = design.assembly.flexion_interval();
    context.out << ", " << report.keyframes << " keyframes over [" << format_human(range ? range->first : f.lower.t)
                << ", " << format_human(range ? range->second : f.upper.t) << "] in " << format_human(o.seconds)
                << " s" << back << '\n';
  }
  if (o.ease > 0.0) {
    context.out << "time linear in t but within " << format_human(o.ease * o.seconds)
                << " s of a flexion limit, where t moves as the square of time (the time map in the file; "
                   "docs/formats.md, \"Time and t\")\n";
  }
  context.out << "largest vertex error between keyframes: " << format_human(report.max_vertex_error) << " ("
              << format_human(report.max_vertex_error / report.model_size) << " of the model size, at t = "
              << format_human(report.vertex_error_t) << "; tolerance " << format_human(o.hinge_tolerance)
              << ", measured at 15 points between every two keyframes)\n";
  if (report.narrow_vertex_error > report.tolerance) {
    context.out << "next to the flexion limits (time linear in t there, --ease 0), within " << format_human(report.narrow_seconds * 1000.0)
                << " ms of the animation in all (keyframes no closer than 0.02 frame at 24 fps; the motion moves as "
                   "the square root of the distance to a limit): up to "
                << format_human(report.narrow_vertex_error / report.model_size) << " of the model size\n";
  }
  if (o.nodes) {
    context.out << "largest hinge opening between keyframes: " << format_human(report.max_opening) << " ("
                << format_human(report.max_opening / report.model_size) << " of the model size)\n";
  }
  const double worst = std::max(report.max_vertex_error, report.max_opening);
  if (worst > report.tolerance) {
    context.err << "phedra: warning: between keyframes the file is " << format_human(worst / report.model_size)
                << " of the model size from the exact motion, more than the tolerance " << format_human(o.hinge_tolerance)
                << (o.nodes ? ": the keyframes are capped; a larger --tolerance keeps it"
                            : ": the morph targets are capped at 250; --nodes (small models) or a larger --tolerance "
                              "keeps it")
                << '\n';
  }
}

/// --layout print: the solids (mm; plates first, then hinge parts) laid flat on
/// beds, the plates named and ordered by their numbers on the cut sheets; one
/// file a bed when they need more than one (parts-1.3mf, parts-2.3mf, ...).
void write_print_beds(Context& context, const Design& design, const GenerateOptions& o, const ThickPlates& plates,
                      std::vector<Solid> solids, std::vector<std::string> names, double mm, const std::string& what) {
  const Vec2 bed = bed_size_from_string(o.bed);
  const std::vector<std::size_t> numbers = plate_sheet_numbers(design);
  std::vector<std::size_t> order(solids.size());
  std::iota(order.begin(), order.end(), 0);
  const std::size_t count = plates.plates();
  auto number = [&](std::size_t k) { return numbers.at(plates.panel(k)); };
  std::stable_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(count),
                   [&](std::size_t a, std::size_t b) { return number(a) < number(b); });
  std::vector<Solid> parts;
  std::vector<std::string> part_names;
  for (const std::size_t k : order) {
    parts.push_back(std::move(solids[k]));
    part_names.push_back(k < count ? "plate_" + std::to_string(number(k)) + "_P" + std::to_string(plates.panel(k))
                                   : names[k]);
  }
  const PrintLayout layout = lay_flat(parts, part_names, bed);
  const std::string ext = std::filesystem::path(o.output).extension().string();
  std::vector<std::pair<std::string, std::string>> files;  // every bed drawn before any is written
  for (std::size_t b = 0; b < layout.beds; ++b) {
    std::vector<Solid> on_bed;
    std::vector<std::string> on_bed_names;
    for (const PrintPart* part : layout.on_bed(b)) {
      on_bed.push_back(part->solid);
      on_bed_names.push_back(part->name);
    }
    files.push_back({numbered(o.output, b, layout.beds),
                     solid_bytes(on_bed, on_bed_names, ext,
                                 what + ", laid flat for printing: bed " + std::to_string(b + 1) + " of " +
                                     std::to_string(layout.beds) + ", " + format_human(bed.x()) + " x " +
                                     format_human(bed.y()) + " mm")});
  }
  for (const auto& [path, content] : files) emit(content, path, o.preset, context.out);
  context.out << "wrote " << (files.size() == 1 ? o.output : files.front().first + " ... " + files.back().first) << ": "
              << count << " plates" << (parts.size() > count ? " and " + std::to_string(parts.size() - count) + " hinge parts" : "")
              << " of \"" << design.assembly.name() << "\" laid flat on " << layout.beds
              << (layout.beds == 1 ? " bed" : " beds") << " of " << format_human(bed.x()) << " x " << format_human(bed.y())
              << " mm (" << (parts.size() > count ? "a plate on its largest face, a knuckle or pin on its end" : "each on its largest face")
              << ", nothing to support; " << format_human(layout.gap) << " mm apart), in millimetres, " << format_human(mm)
              << " mm a model unit; plates named plate_<number>_P<panel> by their numbers on the cut sheets (phedra "
                 "outlines --thickness-mm)\n";
  for (std::size_t b = 0; b < layout.beds && layout.beds > 1; ++b) {
    std::size_t plates_here = 0;
    const std::vector<const PrintPart*> here = layout.on_bed(b);
    for (const PrintPart* part : here) plates_here += part->name.rfind("plate_", 0) == 0;
    context.out << "  bed " << b + 1 << " (" << files[b].first << "): " << plates_here << " plates"
                << (here.size() > plates_here ? ", " + std::to_string(here.size() - plates_here) + " hinge parts" : "")
                << '\n';
  }
}

/// --print-in-place: refused (nothing written) when two bodies are closer than
/// the clearance at t: they would print fused. Parts of hinges too close are
/// moved back by the layout; two plates cannot be.
void refuse_fused(const Design& design, const ThickPlates& plates, const PinLayout& layout, double t, double clearance,
                  std::optional<double> mm) {
  const std::vector<PinCrossing> close = pin_gaps(plates, layout, t, clearance);
  if (close.empty()) return;
  const auto nearest = std::min_element(close.begin(), close.end(),
                                        [](const PinCrossing& a, const PinCrossing& b) { return a.depth < b.depth; });
  const double s = mm ? *mm : 1.0;
  const std::string unit = mm ? " mm" : " model units";
  throw InvalidInputError("--print-in-place", std::to_string(close.size()) + (close.size() == 1 ? " pair" : " pairs") +
                                                  " of parts of different bodies closer than the clearance " +
                                                  format_human(s * clearance) + unit + " at t = " + format_human(t) +
                                                  " (they would print fused): the nearest " + nearest->a + " and " +
                                                  nearest->b + ", " + format_human(s * nearest->depth) + unit +
                                                  " apart; print them at another --at, or with thinner plates (\"" +
                                                  design.assembly.name() + "\")");
}

/// --thickness: every plate a closed solid at t (STL, 3MF, OBJ).
void write_solids(Context& context, const Design& design, const GenerateOptions& o, const BuildabilityReport& buildability,
                  double t) {
  const ThickOptions options = *thick_options(design, o.thickness);
  const ThickReport report = check_thickness(design, buildability, options);
  const ThickPlates plates = thick_plates(design, report);
  std::vector<std::string> names;
  for (std::size_t k = 0; k < plates.plates(); ++k) names.push_back("plate_" + std::to_string(plates.panel(k)));
  const Points positions = plates.positions(t);
  std::vector<Solid> solids = plates.solids(positions);
  double volume = 0.0;
  for (const Solid& solid : solids) volume += solid.volume();
  const std::size_t plate_count = solids.size();
  HingeParts pins;
  PinLayout layout;
  double parts_volume = 0.0;
  const bool in_place = o.thickness.print_in_place;
  std::size_t shells = 0;
  if (o.thickness.hinge == "pin") {  // knuckles and pins after the plates
    // Knuckles kept clear of each other and of the plates at t*, over the thick
    // interval and at t; printed in place, the clearance from other bodies at t.
    std::vector<double> ts = pin_configurations(design.assembly.t_star(), report.thick_lower, report.thick_upper, pin_layout_samples);
    ts.push_back(t);
    const double clearance = in_place_clearance(report.thickness);
    layout = in_place ? pin_layout(plates, ts, InPlace{t, clearance}) : pin_layout(plates, ts);
    pins = pin_hinge_parts(plates, positions, layout);
    for (const Solid& part : pins.solids) parts_volume += part.volume();
    if (in_place) {
      refuse_fused(design, plates, layout, t, clearance, millimetres_per_unit(design, o.thickness));
      InPlaceBodies bodies = in_place_bodies(plates, std::move(solids), pins);
      solids = std::move(bodies.solids);
      names = std::move(bodies.names);
      for (const std::size_t n : bodies.shells) shells += n;
    } else {
      for (std::size_t k = 0; k < pins.solids.size(); ++k) {
        solids.push_back(std::move(pins.solids[k]));
        names.push_back(pins.names[k]);
      }
    }
  }
  // With --thickness-mm the solids are in millimetres, on the cut sheets' scale (a 3MF
  // says millimetre, and slicers read STL and OBJ so); with --thickness, in model units.
  const std::optional<double> mm = millimetres_per_unit(design, o.thickness);
  const double s = mm ? *mm : 1.0;
  const std::string unit = mm ? " mm" : "";
  Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity()), high = -low;
  for (Solid& solid : solids) {
    for (Vec3& v : solid.vertices) {
      v *= s;
      low = low.cwiseMin(v);
      high = high.cwiseMax(v);
    }
  }
  const std::string ext = std::filesystem::path(o.output).extension().string();
  const std::string what = "plates " + format_human(s * report.thickness) + unit + " thick (" + to_string(report.side) + " side)";
  if (o.layout == "print") {
    write_print_beds(context, design, o, plates, std::move(solids), std::move(names), *mm,
                     what + "; phedra buildability: " + buildability.summary());
  } else {
    const Vec3 size = high - low;
    const std::string comment = what + " at t = " + format_human(t) +
                                (mm ? ", millimetres (" + format_human(s) + " mm a model unit)" : ", model units") +
                                "; phedra buildability: " + buildability.summary();
    emit(solid_bytes(solids, names, ext, comment, in_place ? design.assembly.name() + "_in_place" : ""), o.output, o.preset,
         context.out);
    context.out << "wrote " << o.output << ": " << plate_count << " plates " << format_human(s * report.thickness) << unit
                << " thick on the " << to_string(report.side) << " side of \"" << design.assembly.name() << "\" at t = "
                << format_human(t) << ", volume " << format_human(s * s * s * volume) << (mm ? " mm^3" : "")
                << " (thickness x panel area " << format_human(s * s * s * report.thickness * report.panel_area)
                << (mm ? " mm^3" : "") << ")\n";
    context.out << (mm ? "in millimetres, " + format_human(s) + " mm a model unit (the cut sheets' scale)"
                       : std::string("in model units (a slicer reads them as millimetres: --thickness-mm for a size in mm)"))
                << ": overall " << format_human(size.x()) << " x " << format_human(size.y()) << " x "
                << format_human(size.z()) << unit << "\n";
  }
  if (o.thickness.hinge == "pin") {
    const PinSizes sizes(report.thickness);
    context.out << "pin hinges: " << pins.hinges << " hinges, " << pins.knuckles << " knuckles (radius "
                << format_human(s * sizes.knuckle_radius) << unit
                << (in_place ? ", each one with its plate" : ", each a tube joined to a leaf to glue onto its plate's panel face")
                << "), " << pins.pins
                << " pins (radius " << format_human(s * sizes.pin_radius) << unit << ", holes "
                << format_human(s * sizes.hole_radius) << unit << "), volume " << format_human(s * s * s * parts_volume)
                << (mm ? " mm^3" : "") << "; plates cut back by " << format_human(s * 0.5 * report.hinge_gap) << unit
                << " from each hinge line; knuckles kept clear of the hinges they meet at a vertex and of the plates at t* "
                   "and over the thick interval\n";
    if (in_place) {
      context.out << "printed in place: " << solids.size() << " bodies (a plate, its knuckles and the pins one with "
                  << "them; " << shells << " closed shells that touch or overlap, joined by the slicer; "
                  << (ext == ".obj" ? std::string("OBJ objects body_<panel>")
                                    : "one object" + (ext == ".3mf" ? " \"" + design.assembly.name() + "_in_place\"" : std::string()))
                  << "), every part "
                  << "of one at least " << format_human(s * in_place_clearance(report.thickness)) << unit
                  << " from every part of another at t = " << format_human(t)
                  << " (the pin's play in its hole); print with supports, and free every hinge before folding\n";
      if (mm && !o.thickness.printer && s * in_place_clearance(report.thickness) < fdm_printer().clearance_mm) {
        context.err << "phedra: warning: parts printed in place " << format_human(s * in_place_clearance(report.thickness))
                    << " mm apart fuse on an FDM printer (it needs " << format_human(fdm_printer().clearance_mm)
                    << " mm: --printer fdm says the plates and scale that give it; --printer sla: "
                    << format_human(sla_printer().clearance_mm) << " mm)\n";
      }
    }
    if (layout.without_knuckles > 0) {
      context.out << "note: " << layout.without_knuckles << (layout.without_knuckles == 1 ? " hinge" : " hinges")
                  << " left without knuckles (too short for knuckles clear of the other hinges' parts and of the plates"
                  << (in_place ? ", by the clearance" : "") << "): tape or glue them, or thinner plates\n";
    }
  }
  if (report.at_t_star) {
    context.err << "phedra: warning: the plates collide at t* (phedra check --thickness " << format_human(report.thickness)
                << " names them)\n";
  } else if (t < report.thick_lower || t > report.thick_upper) {
    context.err << "phedra: warning: t = " << format_human(t) << " is outside the thick interval ["
                << format_human(report.thick_lower) << ", " << format_human(report.thick_upper)
                << "]: plates collide there (phedra check --thickness)\n";
  }
  // Plates that hardly fold: said in words (as the cut sheets say it), with the thickness that would.
  if (!report.at_t_star && thick_fraction(report) < 0.1) {
    const std::optional<ThickFolding> folding = thickest_folding(design, buildability, options, 0.5);
    const std::vector<std::string> words = plates_fold_words(report, s * report.thickness, s, unit, folding);
    for (std::size_t k = 0; k < words.size(); ++k) context.err << (k ? "; " : "phedra: warning: ") << words[k];
    if (!words.empty()) context.err << '\n';
  }
}

}  // namespace

void add_generate_command(CLI::App& app, Context& context) {
  auto o = std::make_shared<GenerateOptions>();
  CLI::App* sub = app.add_subcommand(
      "generate", "Build the preset's P-hedron, tube or tube array and write it with its folding motion: animated "
                  "glTF (.glb, .gltf), FOLD with frames (.fold), the motion JSON (.json), or a static OBJ/PLY mesh "
                  "(docs/formats.md)");
  add_preset_argument(sub, o->preset);
  sub->add_option("-o,--output", o->output,
                  "Output file: .glb, .gltf, .fold, .json, .obj or .ply; with --thickness .stl, .3mf or .obj")
      ->required();
  sub->add_option("--seconds", o->seconds, "glTF: duration of the motion from t_lambda to t_mu")
      ->check(number_between(0.001, 1e6))
      ->capture_default_str();
  sub->add_flag("--ping-pong", o->ping_pong, "glTF: play t_lambda -> t_mu -> t_lambda");
  sub->add_option("--ease", o->ease,
                  "glTF: fraction of --seconds eased at each flexion limit: time is linear in t but there, where the "
                  "distance to the limit grows as the square of time, so that the motion (which moves as its square "
                  "root) keeps a bounded speed and keyframes can follow it; 0: time linear in t throughout")
      ->check(number_between(0.0, 0.5))
      ->capture_default_str();
  sub->add_option("--at", o->static_t, "glTF: a static export at this t (no animation); OBJ/PLY: the t to write (default t*)")
      ->check(finite_number());
  sub->add_option("--tolerance,--hinge-tolerance", o->hinge_tolerance,
                  "glTF: largest distance of a vertex from its exact place between keyframes (and, with --nodes, "
                  "largest opening of a hinge outside the node tree), relative to the model size")
      ->check(positive_number())
      ->capture_default_str();
  auto* morph = sub->add_flag("--morph", o->morph,
                              "glTF: morph targets, the default: one mesh, one target per keyframe (at most 250), "
                              "sparse one-hot weights; opens and plays at 10^4 panels");
  sub->add_flag("--nodes", o->nodes,
                "glTF: one rigid node per panel on a hinge tree instead (panels exactly rigid between keyframes; "
                "for small models: slow to import above a few thousand panels)")
      ->excludes(morph);
  sub->add_flag("--cycle", o->cycle,
                "glTF: animate the whole configuration curve through the flexion limits (strips switch to their mirror "
                "branch at each limit, see phedra info)");
  sub->add_flag("--no-self-intersection", o->no_self_intersection,
                "Restrict the motion to the intersection-free sub-interval around t* (phedra intersections): the "
                "animation, --count and the frames span it, and a --t, --fraction or --at outside it is refused; "
                "refused when the configuration at t* intersects itself");
  sub->add_option("--intersection-samples", o->intersection_samples,
                  "Samples from t* to each limit for the collision sweep (--no-self-intersection and the buildability "
                  "warning); default 200, fewer above 2000 panels (at least 24)")
      ->check(whole_number_between(1, 1000000));
  add_thickness_options(sub, o->thickness,
                        "Thick plates offset to one side of the panels, bevelled at the hinges, written as solids at "
                        "--at (default t*): .stl (binary), .3mf or .obj, one closed solid a plate (docs/design.md, "
                        "\"Thick panels\")");
  sub->add_option("--layout", o->layout,
                  "Solids: assembled, the plates in place at --at (default t*), or print: every part laid flat on a "
                  "face with nothing to support (a plate on its largest face, a knuckle or pin on its end) and nested on printer beds "
                  "(--bed), plates named plate_<number>_P<panel> by their numbers on the cut sheets; one file a bed "
                  "when they need more than one (parts-1.3mf, parts-2.3mf, ...); needs --thickness-mm")
      ->check(CLI::IsMember({"assembled", "print"}))
      ->capture_default_str();
  auto* bed = sub->add_option("--bed", o->bed, "--layout print: the printer's bed, WxH in mm, parts 5 mm apart and from its edges")
                  ->capture_default_str();
  sub->add_flag("--print-in-place", o->thickness.print_in_place,
                "With --hinge pin: the plates assembled at --at as bodies that print in one piece and move: each plate "
                "with its knuckles and the pins one with them (closed shells that touch or overlap: OBJ objects body_<panel>; "
                "a 3MF holds every body in one object, placed whole), every part of one at least the pin's play (0.05 T; "
                "--printer: its clearance) from every part of another; refused when two would fuse");
  sub->add_flag("-q,--quiet", o->quiet, "No progress bar");
  o->parameters.add_options(sub, 41);
  sub->callback([o, sub, bed, &context] {
    const Format format = format_of(o->output);
    const LoadedDesign loaded = load_with_preset(context, o->preset);
    const Design& design = loaded.design;
    if (o->cycle && format != Format::glb && format != Format::gltf) {
      throw InvalidInputError("--cycle", "the configuration curve is exported as glTF (.glb, .gltf) only");
    }
    if (o->cycle && o->no_self_intersection) {
      throw InvalidInputError("--no-self-intersection", "--cycle runs through the flexion limits; it cannot be "
                                                        "restricted to the intersection-free interval");
    }
    const bool thick = o->thickness.model_units || o->thickness.mm;
    const bool solids = format == Format::stl || format == Format::three_mf || (format == Format::obj && thick);
    if (thick && !solids) {
      throw InvalidInputError("--thickness", "thick plates are written as solids: .stl, .3mf or .obj");
    }
    if (o->layout == "print") {
      if (!o->thickness.mm) {
        throw InvalidInputError("--layout", "parts laid flat on a printer's bed are in millimetres: give --thickness-mm "
                                            "(the plates' thickness in mm; --scale or --model-size for the size)");
      }
      if (!solids) throw InvalidInputError("--layout", "parts laid flat for printing are written as .stl, .3mf or .obj");
      if (o->static_t) throw InvalidInputError("--at", "parts laid flat for printing have no pose: drop --at or --layout print");
      bed_size_from_string(o->bed);  // refused before the work
    } else if (bed->count() > 0) {
      throw InvalidInputError("--bed", "the bed is for parts laid flat: add --layout print");
    }
    if (o->thickness.print_in_place) {
      if (!thick || !solids) throw InvalidInputError("--print-in-place", "parts printed in place are solids: give --thickness or --thickness-mm and .stl, .3mf or .obj");
      if (o->thickness.hinge != "pin") throw InvalidInputError("--print-in-place", "parts printed in place turn on pins: add --hinge pin");
      if (o->layout == "print") {
        throw InvalidInputError("--print-in-place", "parts printed in place are printed assembled; --layout print lays them "
                                                    "apart: choose one");
      }
    }
    if (!thick && (format == Format::stl || format == Format::three_mf)) {
      throw InvalidInputError("--thickness", "an " + std::string(format == Format::stl ? "STL" : "3MF") +
                                                 " file holds solids: give the plate thickness (--thickness T)");
    }
    const BuildabilityReport buildability = assess_for_output(design, o->intersection_samples);
    const std::optional<std::pair<double, double>> range = free_range(context, buildability.motion, *o);
    const FlexionInterval& interval = design.assembly.flexion_interval();
    // What the file holds: the static t, or the animated range.
    auto warn = [&](double lo, double hi) {
      warn_unless_buildable(context, buildability, lo, hi, o->no_self_intersection || o->cycle ? "" : "--no-self-intersection");
    };
    if (format == Format::glb || format == Format::gltf) {
      if (o->static_t) {
        warn(*o->static_t, *o->static_t);
      } else {
        warn(range ? range->first : interval.lower.t, range ? range->second : interval.upper.t);
      }
      write_gltf(context, design, *o, format == Format::glb, range, buildability, loaded.preset);
      return;
    }
    if (solids) {
      const double t = o->static_t.value_or(design.assembly.t_star());
      const FlexionInterval& f = design.assembly.flexion_interval();
      if (!f.contains(t)) throw OutOfIntervalError(t, f.lower.t, f.upper.t);
      check_in_range(t, range);
      warn(t, t);
      write_solids(context, design, *o, buildability, t);
      return;
    }
    if (format == Format::obj || format == Format::ply) {
      const double t = o->static_t.value_or(design.assembly.t_star());
      const FlexionInterval& f = design.assembly.flexion_interval();
      if (!f.contains(t)) throw OutOfIntervalError(t, f.lower.t, f.upper.t);
      check_in_range(t, range);
      warn(t, t);
      emit(mesh_text(design, t, format == Format::obj ? ".obj" : ".ply", "phedra buildability: " + buildability.summary()),
           o->output, o->preset, context.out);
      context.out << "wrote " << o->output << ": " << design.kind << " \"" << design.assembly.name() << "\" at t = "
                  << format_human(t) << '\n';
      return;
    }
    const std::vector<double> ts = range ? o->parameters.values(sub, design.assembly, *range, "--no-self-intersection",
                                                                "intersection-free")
                                         : o->parameters.values(sub, design.assembly);
    warn(*std::min_element(ts.begin(), ts.end()), *std::max_element(ts.begin(), ts.end()));
    if (format == Format::fold) {
      emit(fold_json(design, ts, buildability.file_json()), o->output, o->preset, context.out);
      context.out << "wrote " << o->output << ": " << design.kind << " \"" << design.assembly.name() << "\", "
                  << ts.size() << " frames over [" << format_human(ts.front()) << ", " << format_human(ts.back())
                  << "]\n";
      return;
    }
    MotionDocument document = motion_document(design);
    document.buildability = buildability.file_json();
    emit(motion_json(document, ts), o->output, o->preset, context.out);
    context.out << "wrote " << o->output << ": " << design.kind << " \"" << design.assembly.name() << "\", "
                << document.labels.size() << " vertices, " << document.faces.size() << " faces, " << ts.size()
                << " configurations over [" << format_human(ts.front()) << ", " << format_human(ts.back()) << "]\n";
  });
}

}  // namespace phedra::cli
