// phedra mechanics PRESET [--t T | --fraction F] [--panels n4b5|n5b8] [--bar EA] [--fold KF] [--bend KB]
//                         [--material E,NU --thickness T] [--modes K] [--over-interval N]
//                         [--energy --rest-t T0 | --rest-fraction F0 [--samples N]] [--json] [-o FILE]...

#include "commands.h"
#include "number_checks.h"
#include "support.h"

#include "phedra/errors.h"
#include "phedra/mechanics_charts.h"
#include "phedra/mechanics_report.h"
#include "phedra/number_format.h"
#include "phedra/oscillation_gltf.h"

#include <filesystem>
#include <memory>
#include <ostream>

namespace phedra::cli {
namespace {

struct MechanicsCommandOptions {
  std::string preset;
  std::optional<double> t, fraction;
  std::string panels = "n5b8";
  double bar = 1e3, bend = 0.1;
  std::optional<double> fold;
  std::vector<double> material;
  std::optional<double> thickness, length_scale;
  std::size_t modes = 6;
  std::optional<std::size_t> over_interval;
  bool energy = false;
  std::optional<double> rest_t, rest_fraction;
  std::size_t samples = 201;
  std::string axes = "structural";
  std::vector<std::string> outputs;
  bool json = false;
};

StiffnessOptions stiffness_options(const MechanicsCommandOptions& o) {
  StiffnessOptions s;
  s.panels = parse_panel_model(o.panels);
  s.bar = o.bar;
  s.bend = o.bend;
  s.fold = o.fold;
  if (!o.material.empty()) {
    if (o.material.size() != 2) {
      throw InvalidInputError("--material", "give E,nu (Young's modulus and Poisson's ratio), got " +
                                                std::to_string(o.material.size()) + (o.material.size() == 1 ? " number" : " numbers"));
    }
    if (!o.thickness) throw InvalidInputError("--material", "needs the plate thickness: --thickness T (model units)");
    s.material = Material{o.material[0], o.material[1], *o.thickness, o.length_scale};
  } else if (o.thickness || o.length_scale) {
    throw InvalidInputError(o.thickness ? "--thickness" : "--length-scale", "only with --material E,nu");
  }
  s.validate();
  return s;
}

std::string list(const std::vector<double>& values, std::size_t at_most = 8) {
  std::string out;
  for (std::size_t k = 0; k < values.size() && k < at_most; ++k) out += (k ? "  " : "") + format_human(values[k]);
  if (values.size() > at_most) out += "  ...";
  return out;
}

std::string optional_text(const std::optional<double>& v, const std::string& none) { return v ? format_human(*v) : none; }

void print_modes(std::ostream& out, const ModeAnalysis& a, const StiffnessOptions& s, const BarHingeModel& model) {
  out << "  model: " << a.nodes << " nodes (" << model.corner_node_count() << " corners";
  if (a.nodes > model.corner_node_count()) out << ", " << a.nodes - model.corner_node_count() << " centres";
  out << "), " << a.bars << " bars, " << a.folds << " fold and " << a.bends << " bending hinges";
  if (model.triangle_panels()) out << "; " << model.triangle_panels() << " triangle panels";
  if (model.dropped_faces()) out << "; " << model.dropped_faces() << " shared walls modelled once";
  out << "\n  stiffness: ";
  if (s.material) {
    out << "from the material E " << format_human(s.material->youngs_modulus) << ", nu " << format_human(s.material->poisson)
        << ", thickness " << format_human(s.material->thickness) << " (MERLIN2's calibration)\n";
  } else {
    out << "EA " << format_human(s.bar) << ", KF " << format_human(s.fold_value()) << ", KB " << format_human(s.bend)
        << " (per unit hinge length)\n";
  }
  out << "  rigid-body modes: " << a.rigid_body_modes << " (eigenvalues under 1e-9 of the largest, "
      << format_human(a.largest_eigenvalue) << ")\n";
  std::vector<double> values(a.eigenvalues.data(), a.eigenvalues.data() + a.eigenvalues.size());
  out << "  smallest non-rigid eigenvalues: " << list(values) << "\n";
  out << "  gap (second / first): " << optional_text(a.gap, "none (one mode asked for)") << "\n";
  if (a.motion_alignment) {
    out << "  the exact motion dX/dt: |cos| with mode 1 " << format_human(*a.motion_alignment) << ", stiffness v^T K v / v^T v "
        << format_human(*a.motion_stiffness);
    if (a.motion_in_span.size() >= 2) out << ", in the span of modes 1-2 " << format_human(a.motion_in_span[1]);
    out << "\n";
  } else {
    out << "  the exact motion dX/dt: infinite at a flexion limit (no alignment, no motion stiffness)\n";
  }
}

void print_energy(std::ostream& out, const EnergyLandscape& e) {
  out << "energy landscape: rest state t = " << format_human(e.rest_t) << ", " << e.folds << " fold springs, "
      << e.samples.size() << " samples; largest E " << format_human(e.largest_energy) << "\n";
  for (const Equilibrium& q : e.equilibria) {
    out << "  " << (q.rest ? "rest state (minimum)" : q.minimum ? "minimum" : "maximum") << " at t = " << format_human(q.t)
        << ", E = " << format_human(q.energy) << "\n";
  }
  if (e.bistable()) {
    out << "  bistable: barrier " << format_human(*e.barrier) << " from the rest state, " << format_human(*e.reverse_barrier)
        << " back\n";
  } else {
    out << "  monostable: the rest state is the only minimum over the flexion interval\n";
  }
}

void print_over_interval(std::ostream& out, const ModesOverInterval& m) {
  out << "modes over the flexion interval: " << m.configurations.size() << " configurations, " << m.tracks
      << " tracked modes, " << m.crossings.size() << " crossings\n";
  double gap_lo = INFINITY, gap_hi = -INFINITY, align_lo = INFINITY;
  for (const ModesAt& c : m.configurations) {
    if (c.gap) gap_lo = std::min(gap_lo, *c.gap), gap_hi = std::max(gap_hi, *c.gap);
    if (c.motion_alignment) align_lo = std::min(align_lo, *c.motion_alignment);
  }
  if (std::isfinite(gap_lo)) out << "  gap from " << format_human(gap_lo) << " to " << format_human(gap_hi) << "\n";
  if (std::isfinite(align_lo)) out << "  alignment of mode 1 with the motion at least " << format_human(align_lo) << "\n";
  for (const ModeCrossing& c : m.crossings) {
    out << "  crossing: modes " << c.track_a << " and " << c.track_b << " between t = " << format_human(c.after_t)
        << " and " << format_human(c.before_t) << "\n";
  }
}

/// The modes (and the exact motion) as oscillations of the model at t.
std::string modes_gltf(const BarHingeModel& model, const ModeAnalysis& a, double size, const std::string& name,
                       const std::string& ext, const nlohmann::json& extras) {
  OscillationScene scene;
  scene.name = name;
  scene.positions = model.positions();
  scene.triangles = model.triangles();
  auto field = [&](const std::string& label, const Eigen::VectorXd& v) {
    OscillationField f{label, Points(model.node_count())};
    double largest = 0.0;
    for (std::size_t n = 0; n < model.node_count(); ++n) largest = std::max(largest, v.segment<3>(3 * static_cast<Eigen::Index>(n)).norm());
    for (std::size_t n = 0; n < model.node_count(); ++n) {
      f.displacement[n] = Vec3(largest > 0.0 ? Vec3((0.08 * size / largest) * v.segment<3>(3 * static_cast<Eigen::Index>(n))) : Vec3::Zero());
    }
    scene.fields.push_back(std::move(f));
  };
  for (Eigen::Index k = 0; k < a.modes.cols(); ++k) field("mode " + std::to_string(k + 1), a.modes.col(k));
  if (a.velocity.size() > 0) field("exact motion", a.velocity);
  scene.extras = extras;
  return oscillation_gltf_bytes(scene, ext == ".glb");
}

}  // namespace

void add_mechanics_command(CLI::App& app, Context& context) {
  auto o = std::make_shared<MechanicsCommandOptions>();
  CLI::App* sub = app.add_subcommand(
      "mechanics",
      "Mechanics on the exact motion (MERLIN2's bar-and-hinge definitions): the tangent stiffness at a configuration, its "
      "rigid-body modes and smallest eigenvalues, how the softest mode aligns with the exact motion, the gap, the "
      "motion's stiffness and the mobility; over the interval (--over-interval), or the exact energy landscape from a "
      "rest state (--energy)");
  add_preset_argument(sub, o->preset);
  CLI::Option* t = sub->add_option("--t", o->t, "The configuration: a motion parameter t in [t_lambda, t_mu] (default t*)")
                       ->check(finite_number());
  sub->add_option("--fraction", o->fraction, "The configuration as a fraction F of the flexion interval")
      ->check(number_between(0.0, 1.0))
      ->excludes(t);
  sub->add_option("--panels", o->panels, "n5b8: a centre node, four spokes and four bending hinges a quad (MERLIN2's "
                                        "default); n4b5: each quad split along its shorter diagonal")
      ->capture_default_str();
  sub->add_option("--bar", o->bar, "EA of every bar (MERLIN2's manual mode: 1e3)")->check(positive_number())->capture_default_str();
  sub->add_option("--fold", o->fold, "KF, the fold hinges' stiffness per unit length (default KB / 10)")->check(positive_number());
  sub->add_option("--bend", o->bend, "KB, the bending hinges' stiffness per unit length")->check(positive_number())->capture_default_str();
  sub->add_option("--material", o->material, "E,NU: calibrate bars and hinges from a plate material (MERLIN2's formulas, "
                                             "n5b8), with --thickness")
      ->delimiter(',')
      ->expected(1, 2);
  sub->add_option("--thickness", o->thickness, "The plate thickness for --material (model units)")->check(positive_number());
  sub->add_option("--length-scale", o->length_scale, "L* of the fold stiffness for --material (default twice the mean fold length)")
      ->check(positive_number());
  sub->add_option("--modes", o->modes, "How many of the smallest non-rigid modes")
      ->check(whole_number_between(1, 1000))
      ->capture_default_str();
  CLI::Option* over = sub->add_option("--over-interval", o->over_interval,
                                      "N configurations over the flexion interval: the smallest modes tracked from one to "
                                      "the next, crossings flagged, the gap (CSV, JSON, SVG or PNG with -o)")
                            ->check(whole_number_between(2, 100000));
  sub->add_flag("--energy", o->energy,
                                      "The exact energy landscape of the motion from a rest state (--rest-t or "
                                      "--rest-fraction): E(t), dE/dt, equilibria, bistability, forces (CSV, JSON, SVG or PNG with -o)")
                            ->excludes(over);
  CLI::Option* rest_t = sub->add_option("--rest-t", o->rest_t, "The rest state T0 (stress-free: how the piece was made) for --energy")
                            ->check(finite_number());
  sub->add_option("--rest-fraction", o->rest_fraction, "The rest state as a fraction of the flexion interval")
      ->check(number_between(0.0, 1.0))
      ->excludes(rest_t);
  sub->add_option("--samples", o->samples, "--energy: samples over the flexion interval, both limits included (the rest state is added)")
      ->check(whole_number_between(2, 1000000))
      ->capture_default_str();
  sub->add_option("--axes", o->axes, "--energy: the axes of the forces, as `phedra metrics` (structural or xyz)")
      ->capture_default_str();
  sub->add_option("-o,--output", o->outputs,
                  "Write: .glb or .gltf (the modes at the configuration, animated), .json (everything), and with "
                  "--over-interval or --energy .csv, .svg or .png (the plot); repeatable")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  sub->add_flag("--json", o->json, "Print the JSON on standard output instead of the summary");
  sub->callback([o, &context] {
    const bool plots = o->over_interval || o->energy;
    for (const std::string& path : o->outputs) {
      const std::string ext = std::filesystem::path(path).extension().string();
      const bool known = ext == ".json" || ext == ".glb" || ext == ".gltf" || ext == ".csv" || ext == ".svg" || ext == ".png";
      if (!known) {
        throw InvalidInputError("--output", "unknown format \"" + ext + "\" for " + path +
                                                " (use .glb or .gltf, .json, .csv, .svg or .png)");
      }
      if (!plots && (ext == ".csv" || ext == ".svg" || ext == ".png")) {
        throw InvalidInputError("--output", path + ": " + ext + " is a plot or table of --over-interval or --energy; "
                                            "at one configuration write .json or .glb");
      }
    }
    if (o->energy && !o->rest_t && !o->rest_fraction) {
      throw InvalidInputError("--energy", "needs the rest state: --rest-t T0 or --rest-fraction F0");
    }
    if (!o->energy && (o->rest_t || o->rest_fraction)) {
      throw InvalidInputError(o->rest_t ? "--rest-t" : "--rest-fraction", "only with --energy");
    }
    const StiffnessOptions stiffness = stiffness_options(*o);
    const Design design = load(context, o->preset);
    const Assembly& a = design.assembly;
    const double lo = a.flexion_interval().lower.t, hi = a.flexion_interval().upper.t;
    auto at_fraction = [&](double f, const std::string& option) {
      if (!(f >= 0.0 && f <= 1.0)) {
        throw InvalidInputError(option, "must be in [0, 1] (0: t_lambda, 1: t_mu), got " + format_number(f));
      }
      return a.t_at_fraction(f);
    };
    auto inside = [&](double value, const std::string& option, const std::string& what) {
      if (!(value >= lo && value <= hi)) {
        throw InvalidInputError(option, what + " t = " + format_number(value) + " is outside the flexion interval [" +
                                            format_number(lo) + ", " + format_number(hi) + "]");
      }
      return value;
    };
    MechanicsRequest request;
    request.t = o->t ? inside(*o->t, "--t", "the configuration")
                     : o->fraction ? at_fraction(*o->fraction, "--fraction") : a.t_star();
    request.stiffness = stiffness;
    request.modes = o->modes;
    request.over_interval = o->over_interval;
    if (o->energy) {
      EnergyOptions e;
      e.rest_t = o->rest_t ? inside(*o->rest_t, "--rest-t", "the rest state") : at_fraction(*o->rest_fraction, "--rest-fraction");
      e.samples = o->samples;
      e.axes = parse_metrics_axes(o->axes);
      request.energy = e;
    }
    const MechanicsReport report = mechanics_report(design, request);
    const nlohmann::json document = report.to_json();

    for (const std::string& path : o->outputs) {
      const std::string ext = std::filesystem::path(path).extension().string();
      std::string content;
      if (ext == ".json") {
        content = document.dump(2) + "\n";
      } else if (ext == ".glb" || ext == ".gltf") {
        const nlohmann::json extras = {{"name", a.name()},
                                       {"t", report.t},
                                       {"model_size", a.model_size()},
                                       {"panels", to_string(stiffness.panels)},
                                       {"eigenvalues", document["eigenvalues"]},
                                       {"motion_alignment", document["motion_alignment"]},
                                       {"fields", "the modes in order, then the exact motion (each one oscillation)"}};
        content = modes_gltf(*report.model, report.modes, a.model_size(), a.name(), ext, extras);
      } else if (ext == ".csv") {
        content = report.energy ? report.energy->to_csv() : report.over_interval->to_csv();
      } else {
        const Chart chart = report.energy ? energy_chart(*report.energy) : modes_chart(*report.over_interval);
        content = ext == ".svg" ? chart_svg(chart) : chart_png(chart);
      }
      emit(content, path, o->preset, context.out);
    }
    if (o->json) {
      context.out << document.dump(2) << '\n';
      return;
    }
    context.out << "mechanics: " << a.name() << " (" << design.kind << "), " << to_string(stiffness.panels) << " at t = "
                << format_human(report.t) << (report.t == a.t_star() ? " (t*)" : "") << "\n";
    print_modes(context.out, report.modes, stiffness, *report.model);
    context.out << report.mobility;
    if (report.over_interval) print_over_interval(context.out, *report.over_interval);
    if (report.energy) print_energy(context.out, *report.energy);
    for (const std::string& path : o->outputs) context.out << "wrote " << path << '\n';
  });
}

}  // namespace phedra::cli
