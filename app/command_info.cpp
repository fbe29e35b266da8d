// phedra info PRESET [--json]: t*, case, flexion interval, counts, and the
// planarity/isometry figures at t*.

#include "commands.h"
#include "phedra/control_polylines.h"
#include "phedra/interval_check.h"
#include "phedra/number_format.h"
#include "support.h"

#include <memory>
#include <ostream>

namespace phedra::cli {
namespace {

struct InfoOptions {
  std::string preset;
  bool json = false;
};

std::string limit_cause(std::size_t strip) {
  if (strip == 0) return "linkage L_0 (V_{0,0} reaches the axis)";
  return "strip " + std::to_string(strip) + " (profile planes " + std::to_string(strip - 1) + " and " +
         std::to_string(strip) + " coincide)";
}

nlohmann::json info_json(const PHedron& p, const IntervalCheckReport& at_star) {
  const FlexionInterval& f = p.flexion_interval();
  const GridTopology& g = p.topology();
  return {{"name", p.input().name},
          {"t_star", p.t_star()},
          {"case", to_string(p.motion_case())},
          {"moving_apex", p.motion_case() == MotionCase::a ? "S_0" : "S_1"},
          {"flexion_interval", {f.lower.t, f.upper.t}},
          {"limits",
           {{{"t", f.lower.t}, {"strip", f.lower.strip}, {"cause", limit_cause(f.lower.strip)}},
            {{"t", f.upper.t}, {"strip", f.upper.strip}, {"cause", limit_cause(f.upper.strip)}}}},
          {"profiles", g.rows()},
          {"profile_vertices", p.profile_vertex_count()},
          {"signs", signs_to_string(p.input().signs)},
          {"rows", g.rows()},
          {"columns", g.columns()},
          {"vertices", g.vertex_count()},
          {"faces", g.faces().size()},
          {"edges", g.edges().size()},
          {"model_size", p.model_size()},
          {"planarity", at_star.planarity.value},
          {"isometry", at_star.isometry.value},
          {"reproduction", at_star.reproduction},
          {"at_t_star", at_star.to_json()}};
}

void print_info(std::ostream& out, const PHedron& p, const IntervalCheckReport& at_star) {
  const FlexionInterval& f = p.flexion_interval();
  const GridTopology& g = p.topology();
  const double size = p.model_size();
  out << "name:              " << p.input().name << '\n'
      << "profiles:          " << g.rows() << " (m = " << g.rows() - 1 << " strips), n = " << p.profile_vertex_count()
      << " vertices each, signs " << signs_to_string(p.input().signs) << '\n'
      << "mesh:              " << g.vertex_count() << " vertices (" << g.rows() << " x " << g.columns()
      << " grid with boundary columns), " << g.faces().size() << " faces, " << g.edges().size() << " edges\n"
      << "motion parameter:  case (" << to_string(p.motion_case()) << "), t = axis coordinate of "
      << (p.motion_case() == MotionCase::a ? "S_0" : "S_1") << '\n'
      << "t*:                " << format_number(p.t_star()) << '\n'
      << "flexion interval:  [" << format_number(f.lower.t) << ", " << format_number(f.upper.t) << "]\n"
      << "  t_lambda limit:  " << limit_cause(f.lower.strip) << '\n'
      << "  t_mu limit:      " << limit_cause(f.upper.strip) << '\n'
      << "model size:        " << format_number(size) << " (bounding-box diagonal at t*)\n"
      << "at t*:             planarity " << format_number(at_star.planarity.value / size) << ", isometry "
      << format_number(at_star.isometry.value / size) << ", reproduction "
      << format_number(at_star.reproduction / size) << " (relative to the model size)\n";
}

}  // namespace

void add_info_command(CLI::App& app, Context& context) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* sub = app.add_subcommand("info", "Show t*, the motion case, the flexion interval with its limits, "
                                              "the mesh counts and the planarity/isometry at t*");
  sub->add_option("preset", options->preset, "Preset file (JSON, docs/presets.md)")->required();
  sub->add_flag("--json", options->json, "Print JSON instead of text");
  sub->callback([options, &context] {
    const PHedron p = load_phedron(context, options->preset);
    const IntervalCheckReport at_star = check_at_t_star(p);
    if (options->json) {
      context.out << info_json(p, at_star).dump(2) << '\n';
    } else {
      print_info(context.out, p, at_star);
    }
  });
}

}  // namespace phedra::cli
