// phedra info PRESET [--json]: what the preset builds, t*, case, flexion interval
// with its limits, counts, and the figures at t*.

#include "commands.h"
#include "phedra/assembly_check.h"
#include "phedra/control_polylines.h"
#include "phedra/number_format.h"
#include "phedra/self_intersection.h"
#include "buildability_warning.h"
#include "support.h"
#include "phedra/motion_document.h"
#include "phedra/check_report.h"

#include <algorithm>
#include <memory>
#include <ostream>

namespace phedra::cli {
namespace {

struct InfoOptions {
  std::string preset;
  bool json = false;
};

/// The strips a branch has switched, "input branch" for none.
std::string branch_name(const std::vector<bool>& flipped) {
  std::string s;
  for (std::size_t i = 1; i < flipped.size(); ++i) {
    if (flipped[i]) s += (s.empty() ? "strips " : ", ") + std::to_string(i);
  }
  return s.empty() ? "input branch" : s + " mirrored";
}

nlohmann::json curve_json(const PHedron::ConfigurationCycle& c) {
  nlohmann::json passes = nlohmann::json::array();
  for (const PHedron::Pass& p : c.passes) {
    std::vector<std::size_t> mirrored;
    for (std::size_t i = 1; i < p.flipped.size(); ++i) {
      if (p.flipped[i]) mirrored.push_back(i);
    }
    passes.push_back({{"from", p.from}, {"to", p.to}, {"switched_strip", p.switched}, {"mirrored_strips", mirrored}});
  }
  nlohmann::json j{{"closed", c.closed}, {"passes", passes}};
  if (!c.stop.empty()) j["stop"] = c.stop;
  return j;
}

nlohmann::json info_json(const Design& design, const MotionDocument& mesh, const AssemblyCheckReport& at_star) {
  const Assembly& a = design.assembly;
  const PHedron& p = a.base();
  const FlexionInterval& f = a.flexion_interval();
  const GridTopology& g = p.topology();
  nlohmann::json members = nlohmann::json::array();
  for (std::size_t m = 0; m < a.member_count(); ++m) members.push_back(a.member_name(m));
  nlohmann::json j{{"name", a.name()},
                   {"kind", design.kind},
                   {"t_star", a.t_star()},
                   {"case", to_string(p.motion_case())},
                   {"moving_apex", p.motion_case() == MotionCase::a ? "S_0" : "S_1"},
                   {"flexion_interval", {f.lower.t, f.upper.t}},
                   {"limits",
                    {{{"t", f.lower.t}, {"strip", f.lower.strip}, {"cause", f.lower.cause()}},
                     {{"t", f.upper.t}, {"strip", f.upper.strip}, {"cause", f.upper.cause()}}}},
                   {"profiles", g.rows()},
                   {"profile_vertices", p.profile_vertex_count()},
                   {"signs", signs_to_string(p.input().signs)},
                   {"closed", p.closed()},
                   {"members", a.member_count()},
                   {"member_names", members},
                   {"merged", design.merge},
                   {"vertices", mesh.labels.size()},
                   {"faces", mesh.faces.size()},
                   {"shared_vertex_groups", a.shared_vertices().size()},
                   {"model_size", a.model_size()},
                   {"planarity", at_star.planarity.value},
                   {"isometry", at_star.isometry.value},
                   {"closure", at_star.closure.value},
                   {"reproduction", at_star.reproduction},
                   {"at_t_star", report_json(at_star)}};
  j["configuration_curve"] = curve_json(p.configuration_cycle());
  if (a.member_count() == 1) {
    j["rows"] = g.rows();
    j["columns"] = g.columns();
    j["edges"] = g.edge_count();
  }
  if (!at_star.warning.empty()) j["warning"] = at_star.warning;
  if (!p.input().trajectory_source.empty()) j["trajectory_source"] = p.input().trajectory_source;
  return j;
}

nlohmann::json panels_json(const BuildabilityReport& b) {
  return {{"distinct", b.panels},
          {"shared_walls", b.shared_walls},
          {"bow_tie", b.count(PanelShape::bow_tie)},
          {"degenerate", b.count(PanelShape::degenerate)},
          {"self_intersection_at_t_star",
           b.motion.at_t_star ? nlohmann::json(describe(*b.motion.at_t_star, b.members > 1)) : nullptr}};
}

void print_panels(std::ostream& out, const BuildabilityReport& b) {
  out << "buildability:      " << b.summary() << '\n';
  if (!b.buildable()) out << "                   (phedra check names the cause of each invalid panel and the field to change)\n";
}

void print_info(std::ostream& out, const Design& design, const MotionDocument& mesh, const AssemblyCheckReport& at_star) {
  const Assembly& a = design.assembly;
  const PHedron& p = a.base();
  const FlexionInterval& f = a.flexion_interval();
  const GridTopology& g = p.topology();
  const double size = a.model_size();
  out << "name:              " << a.name() << '\n'
      << "kind:              " << design.kind << '\n'
      << "profiles:          " << g.rows() << " (m = " << g.rows() - 1 << " strips), n = " << p.profile_vertex_count()
      << " vertices each, signs " << signs_to_string(p.input().signs) << '\n';
  if (!p.input().trajectory_source.empty()) out << "trajectory:        " << p.input().trajectory_source << '\n';
  if (a.member_count() == 1) {
    out << "mesh:              " << g.vertex_count() << " vertices (" << g.rows() << " x " << g.columns()
        << (p.closed() ? " grid, cyclic columns), " : " grid with boundary columns), ") << g.face_count()
        << " faces, " << g.edge_count() << " edges\n";
  } else {
    out << "members:           " << a.member_count() << " (" << a.member_name(0) << ", ..., "
        << a.member_name(a.member_count() - 1) << "), " << a.shared_vertices().size() << " shared vertex groups\n"
        << "mesh:              " << mesh.labels.size() << " vertices, " << mesh.faces.size() << " panels"
        << (design.merge ? " (merged: shared vertices welded, shared face strips deleted)"
                         : " (shared vertices welded, a wall two cells share is one panel)")
        << '\n';
  }
  out << "motion parameter:  case (" << to_string(p.motion_case()) << "), t = axis coordinate of "
      << (p.motion_case() == MotionCase::a ? "S_0" : "S_1") << '\n'
      << "t*:                " << format_human(a.t_star()) << '\n'
      << "flexion interval:  [" << format_human(f.lower.t) << ", " << format_human(f.upper.t) << "]\n"
      << "  t_lambda limit:  " << f.lower.cause() << '\n'
      << "  t_mu limit:      " << f.upper.cause() << '\n';
  {
    // The whole curve through the limits (paper, Remark 3); an array's members follow its base.
    const PHedron::ConfigurationCycle c = p.configuration_cycle();
    out << "configuration curve: " << c.passes.size() << " passes, "
        << (c.closed ? "closed (back at t* on the input branch)" : "open: " + c.stop) << '\n';
    for (const PHedron::Pass& pass : c.passes) {
      out << "  " << (pass.switched ? "strip " + std::to_string(pass.switched) + " switches, " : std::string())
          << "t " << format_human(pass.from) << " -> " << format_human(pass.to) << "  (" << branch_name(pass.flipped)
          << ")\n";
    }
  }
  out
      << "model size:        " << format_human(size) << " (bounding-box diagonal at t*)\n"
      << "at t*:             planarity " << format_human(at_star.planarity.value / size) << ", isometry "
      << format_human(at_star.isometry.value / size) << ", reproduction "
      << format_human(at_star.reproduction / size);
  if (at_star.closed) out << ", closure " << format_human(at_star.closure.value / size);
  if (a.member_count() > 1) out << ", shared mismatch " << format_human(at_star.shared.value / size);
  out << " (relative to the model size)\n";
  if (!at_star.warning.empty()) out << "warning:           " << at_star.warning << '\n';
}

}  // namespace

void add_info_command(CLI::App& app, Context& context) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* sub = app.add_subcommand("info", "Show what the preset builds, t*, the motion case, the flexion interval "
                                              "with its limits, the configuration curve through them (strips switching "
                                              "branch), the mesh counts and the figures at t*");
  add_preset_argument(sub, options->preset);
  sub->add_flag("--json", options->json, "Print JSON instead of text");
  sub->callback([options, &context] {
    const Design design = load(context, options->preset);
    const MotionDocument mesh = motion_document(design);
    const AssemblyCheckReport at_star = check_assembly_at_t_star(design.assembly);
    const BuildabilityReport buildability = assess_for_output(design);
    if (options->json) {
      nlohmann::json j = info_json(design, mesh, at_star);
      j["panels"] = panels_json(buildability);
      j["buildability"] = buildability.file_json();
      context.out << j.dump(2) << '\n';
    } else {
      print_info(context.out, design, mesh, at_star);
      print_panels(context.out, buildability);
    }
  });
}

}  // namespace phedra::cli
