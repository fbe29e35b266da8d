#include "phedra/buildability.h"

#include "phedra/field_hints.h"

#include "phedra/number_format.h"

#include <algorithm>
#include <limits>
#include <ostream>

namespace phedra {
namespace {

std::string plural(std::size_t count, const std::string& word) {
  return std::to_string(count) + " " + word + (count == 1 ? "" : "s");
}

std::string interval_text(double a, double b) { return "[" + format_human(a) + ", " + format_human(b) + "]"; }

/// An anti-parallelogram tube: a closed member with '-' signs (MATH.md section 6).
bool self_crossing_kind(const Assembly& a, std::size_t m) {
  if (!a.closed(m)) return false;
  const std::vector<Sign>& signs = a.signs(m);
  return !signs.empty() && std::all_of(signs.begin(), signs.end(), [](Sign s) { return s == Sign::minus; });
}

nlohmann::json hint_json(const FieldHint& h) {
  return {{"field", h.field}, {"value", h.value}, {"change", h.change}, {"text", describe(h)}};
}

}  // namespace

std::size_t sweep_samples_for(std::size_t panels) {
  if (panels <= 2000) return 200;
  return std::max<std::size_t>(24, 400000 / panels);
}

std::size_t BuildabilityReport::count(PanelShape shape) const {
  return static_cast<std::size_t>(
      std::count_if(invalid.begin(), invalid.end(), [shape](const PanelDiagnosis& d) { return d.shape == shape; }));
}

std::optional<std::pair<double, double>> BuildabilityReport::interval() const {
  if (!panels_simple() || motion.at_t_star || !self_crossing_members.empty()) return std::nullopt;
  return std::pair<double, double>{motion.free_lower, motion.free_upper};
}

bool BuildabilityReport::buildable_over(double a, double b) const {
  const auto range = interval();
  if (!range || !swept) return false;
  const double slack = 1e-12 * std::max(t_mu - t_lambda, 0.0);
  return std::min(a, b) >= range->first - slack && std::max(a, b) <= range->second + slack;
}

std::string BuildabilityReport::invalid_list(std::size_t shown) const {
  std::string s;
  for (std::size_t k = 0; k < std::min(shown, invalid.size()); ++k) s += (k ? ", " : "") + std::to_string(invalid[k].panel);
  if (invalid.size() > shown) s += " (and " + std::to_string(invalid.size() - shown) + " more)";
  return s;
}

std::string BuildabilityReport::summary() const {
  const bool several = members > 1;
  std::string s;
  if (!self_crossing_members.empty()) {
    s = "not buildable, by its kind: an anti-parallelogram tube's walls cross each other along a line at every t "
        "(its linkage L_0 is a crossed four-bar, MATH.md section 6); no choice of numbers changes that";
    if (!panels_simple()) s += "; also " + plural(invalid.size(), "panel") + " not simple (" + invalid_list() + ")";
    return s;
  }
  if (!panels_simple()) {
    const std::size_t bow = count(PanelShape::bow_tie), flat = count(PanelShape::degenerate);
    const std::size_t big = count(PanelShape::oversized), thin = count(PanelShape::sliver);
    std::vector<std::string> kinds;
    if (bow) kinds.push_back(plural(bow, "bow-tie"));
    if (flat) kinds.push_back(std::to_string(flat) + " degenerate");
    if (big) kinds.push_back(std::to_string(big) + " oversized");
    if (thin) kinds.push_back(plural(thin, "sliver"));
    s = "not buildable: " + std::to_string(invalid.size()) + " of " + std::to_string(panels) + " panels " +
        (big + thin ? "cannot be built (" : "cannot be cut as one plate (");
    for (std::size_t k = 0; k < kinds.size(); ++k) s += (k ? ", " : "") + kinds[k];
    s += ": panel" + std::string(invalid.size() == 1 ? " " : "s ") + invalid_list() + ")";
    if (motion.at_t_star) s += "; at t* " + describe(*motion.at_t_star, several);
    return s;
  }
  if (motion.at_t_star) return "not buildable: the configuration at t* intersects itself: " + describe(*motion.at_t_star, several);
  if (!swept) return "every panel is simple and t* is free of collisions (the motion was not swept)";
  const std::string coarse = motion.samples < 200 ? " (swept at " + std::to_string(motion.samples) + " samples a side)" : "";
  if (buildable()) return "buildable over the whole flexion interval " + interval_text(t_lambda, t_mu) + coarse;
  const double width = t_mu - t_lambda;
  const double share = width > 0.0 ? 100.0 * (motion.free_upper - motion.free_lower) / width : 0.0;
  return "buildable over " + interval_text(motion.free_lower, motion.free_upper) + " only (" + format_short(share) +
         " % of the flexion interval " + interval_text(t_lambda, t_mu) + ")" + coarse;
}

nlohmann::json BuildabilityReport::to_json() const {
  nlohmann::json list = nlohmann::json::array();
  for (const PanelDiagnosis& d : invalid) {
    nlohmann::json hints = nlohmann::json::array();
    for (const FieldHint& h : d.hints) hints.push_back(hint_json(h));
    list.push_back({{"panel", d.panel},
                    {"member", d.member},
                    {"strip", d.strip},
                    {"column", d.column},
                    {"shape", to_string(d.shape)},
                    {"cause", to_string(d.rule.cause)},
                    {"why", d.why},
                    {"hints", hints}});
  }
  const auto range = interval();
  nlohmann::json crossing = nlohmann::json::array();
  for (std::size_t m : self_crossing_members) crossing.push_back(m);
  nlohmann::json collision = nlohmann::json::array();
  for (const FieldHint& h : collision_hints) collision.push_back(hint_json(h));
  return {{"buildable", buildable()},
          {"summary", summary()},
          {"panels", panels},
          {"shared_walls", shared_walls},
          {"shape_margin", shape_margin},
          {"bow_tie", count(PanelShape::bow_tie)},
          {"degenerate", count(PanelShape::degenerate)},
          {"oversized", count(PanelShape::oversized)},
          {"sliver", count(PanelShape::sliver)},
          {"invalid_panels", list},
          {"self_crossing_members", crossing},
          {"collision_hints", collision},
          {"swept", swept},
          {"buildable_interval", range ? nlohmann::json{range->first, range->second} : nlohmann::json(nullptr)},
          {"flexion_interval", {t_lambda, t_mu}},
          {"motion", motion.to_json()}};
}

nlohmann::json BuildabilityReport::file_json() const {
  nlohmann::json panels_list = nlohmann::json::array(), shapes = nlohmann::json::array();
  for (const PanelDiagnosis& d : invalid) {
    panels_list.push_back(d.panel);
    shapes.push_back(to_string(d.shape));
  }
  const auto range = interval();
  nlohmann::json j{{"buildable", buildable()},
                   {"summary", summary()},
                   {"panels", panels},
                   {"bow_tie", count(PanelShape::bow_tie)},
                   {"degenerate", count(PanelShape::degenerate)},
                   {"oversized", count(PanelShape::oversized)},
                   {"sliver", count(PanelShape::sliver)},
                   {"invalid_panels", panels_list},
                   {"invalid_shapes", shapes},
                   {"self_crossing_by_kind", !self_crossing_members.empty()},
                   {"samples_per_side", swept ? nlohmann::json(motion.samples) : nlohmann::json(nullptr)},
                   {"buildable_interval", range ? nlohmann::json{range->first, range->second} : nlohmann::json(nullptr)}};
  if (motion.at_t_star) j["collision_at_t_star"] = describe(*motion.at_t_star, members > 1);
  return j;
}

std::ostream& operator<<(std::ostream& out, const BuildabilityReport& r) {
  const bool several = r.members > 1;
  out << "buildability: " << r.summary() << '\n';
  out << "  panels: " << r.panels << " distinct";
  if (r.shared_walls) out << " (" << plural(r.shared_walls, "wall") << " shared by two cells, counted once)";
  out << ", " << r.count(PanelShape::bow_tie) << " bow-tie, " << r.count(PanelShape::degenerate) << " degenerate";
  if (r.count(PanelShape::oversized)) out << ", " << r.count(PanelShape::oversized) << " oversized";
  if (r.count(PanelShape::sliver)) out << ", " << plural(r.count(PanelShape::sliver), "sliver");
  out << '\n';
  const std::size_t detail = 8;
  for (std::size_t k = 0; k < std::min(detail, r.invalid.size()); ++k) {
    const PanelDiagnosis& d = r.invalid[k];
    PanelId id{d.panel, d.member, d.strip, d.column, d.shared_with};
    out << "  " << describe(id, several) << " is " << (d.shape == PanelShape::bow_tie ? "a bow-tie" : to_string(d.shape))
        << ": " << d.why << '\n';
    if (!d.hints.empty()) {
      out << "    change: ";
      for (std::size_t h = 0; h < d.hints.size(); ++h) out << (h ? "; or " : "") << describe(d.hints[h]);
      out << '\n';
    }
  }
  if (r.invalid.size() > detail) {
    out << "  ... and " << r.invalid.size() - detail << " more (--json lists every panel with its cause)\n";
  }
  if (!r.collision_hints.empty()) {
    out << "    change: ";
    for (std::size_t h = 0; h < r.collision_hints.size(); ++h) out << (h ? "; or " : "") << describe(r.collision_hints[h]);
    out << (r.motion.at_t_star->kind == Collision::Kind::hinge ? " (to open that hinge to 10 degrees)" : " (to part those panels)")
        << '\n';
  }
  if (r.swept && !r.motion.at_t_star) {
    if (r.motion.lower) out << "  below t = " << format_human(r.motion.lower->t) << ": " << describe(*r.motion.lower, several) << '\n';
    if (r.motion.upper) out << "  above t = " << format_human(r.motion.upper->t) << ": " << describe(*r.motion.upper, several) << '\n';
    if (r.motion.lower_contact) out << "  at t_lambda the panels touch (allowed at a flexion limit): " << describe(*r.motion.lower_contact, several, true) << '\n';
    if (r.motion.upper_contact) out << "  at t_mu the panels touch (allowed at a flexion limit): " << describe(*r.motion.upper_contact, several, true) << '\n';
  }
  return out;
}

BuildabilityReport assess_buildability(const Design& design, const nlohmann::json* preset, const BuildabilityOptions& options) {
  const Assembly& a = design.assembly;
  const AssemblyMesh mesh = panel_mesh(design);
  BuildabilityReport r;
  r.name = a.name();
  r.kind = design.kind;
  r.panels = mesh.faces.size();
  r.shared_walls = mesh.shared_walls;
  r.members = a.member_count();
  r.t_star = a.t_star();
  r.t_lambda = a.flexion_interval().lower.t;
  r.t_mu = a.flexion_interval().upper.t;
  DiagnosisOptions diagnosis = options.diagnosis;
  diagnosis.size = options.bounds;
  r.invalid = diagnose_panels(design, mesh, preset, diagnosis);
  r.shape_margin = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    r.shape_margin = std::min(r.shape_margin, shape_margin(panel_nets(a, mesh.face_member[f], mesh.face_local[f])));
  }
  for (std::size_t m = 0; m < a.member_count(); ++m) {
    if (self_crossing_kind(a, m)) r.self_crossing_members.push_back(m);
  }
  r.swept = options.sweep_motion;
  SelfIntersectionOptions sweep = options.sweep;
  sweep.max_growth = options.bounds.max_growth;
  if (sweep.samples_per_side == 0) sweep.samples_per_side = sweep_samples_for(r.panels);
  if (options.sweep_motion) {
    r.motion = find_self_intersections(design, sweep);
  } else {
    r.motion.name = r.name;
    r.motion.t_star = r.motion.free_lower = r.motion.free_upper = r.t_star;
    r.motion.t_lambda = r.t_lambda;
    r.motion.t_mu = r.t_mu;
    r.motion.members = r.members;
    r.motion.panels = r.panels;
    r.motion.model_size = a.model_size();
    r.motion.at_t_star = self_intersection_at_t_star(design, sweep);
  }
  if (r.motion.at_t_star && preset != nullptr && options.diagnosis.hints && r.panels_simple()) {
    r.collision_hints = collision_hints(*preset, design, *r.motion.at_t_star);
  }
  return r;
}

}  // namespace phedra
