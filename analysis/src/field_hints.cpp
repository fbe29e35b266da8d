#include "phedra/field_hints.h"

#include "phedra/errors.h"
#include "phedra/panel_nets.h"
#include "phedra/panel_size.h"
#include "phedra/design_preset.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace phedra {
namespace {

using json = nlohmann::json;
using Pointer = json::json_pointer;

void add_numbers(std::vector<DesignField>& out, const json& array, const Pointer& at, const std::string& name,
                 DesignField::Group group, double scale) {
  if (!array.is_array()) return;
  for (std::size_t k = 0; k < array.size(); ++k) {
    if (array[k].is_number()) out.push_back({name + "[" + std::to_string(k) + "]", at / k, group, std::nullopt, scale});
  }
}

/// Points [[x, y, z], ...]: one field per coordinate, rows = point indices.
void add_points(std::vector<DesignField>& out, const json& points, const Pointer& at, const std::string& name,
                DesignField::Group group, double model_size, bool rows) {
  if (!points.is_array()) return;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const json& p = points[i];
    if (!p.is_array()) continue;
    double scale = model_size;
    if (group == DesignField::Group::directions) {
      double norm2 = 0.0;
      for (const json& c : p) norm2 += c.is_number() ? c.get<double>() * c.get<double>() : 0.0;
      scale = std::sqrt(norm2) > 0.0 ? std::sqrt(norm2) : 1.0;
    }
    for (std::size_t c = 0; c < p.size(); ++c) {
      if (!p[c].is_number()) continue;
      out.push_back({name + "[" + std::to_string(i) + "][" + std::to_string(c) + "]", at / i / c, group,
                     rows ? std::optional<std::size_t>(i) : std::nullopt, scale});
    }
  }
}

/// What a field moves, zero where the goal is reached: the corner turns of a
/// member face's general net (canonical) along `normal` over model_size^2; an
/// edge's target length over its length, less 1; the aspect over its bound,
/// less 1 (unused entries NaN: no slope).
std::array<double, 4> measure(const Assembly& a, const MemberFace& f, const HintGoal& goal, const Vec3& normal, double size2) {
  const PanelCorners g = panel_nets(a, f.member, f.local).general;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (goal.kind == HintGoal::Kind::edge) {
    // The target over the length: nearly linear where two nearly parallel lines meet far out.
    return {goal.value / (g[(goal.edge + 1) % 4] - g[goal.edge]).norm() - 1.0, nan, nan, nan};
  }
  if (goal.kind == HintGoal::Kind::aspect) {
    return {quad_area(g) / longest_edge_squared(g) / goal.value - 1.0, nan, nan, nan};
  }
  std::array<double, 4> t = corner_turns(g, normal);
  for (double& v : t) v /= size2;
  return t;
}

}  // namespace

std::vector<DesignField> design_fields(const json& preset, double model_size) {
  std::vector<DesignField> out;
  const Pointer root;
  const auto heights = DesignField::Group::heights;
  if (preset.contains("apex_heights")) add_numbers(out, preset["apex_heights"], root / "apex_heights", "apex_heights", heights, model_size);
  if (preset.contains("tube") && preset["tube"].is_object() && preset["tube"].contains("apex_heights")) {
    add_numbers(out, preset["tube"]["apex_heights"], root / "tube" / "apex_heights", "tube.apex_heights", heights, model_size);
  }
  if (preset.contains("grid") && preset["grid"].is_object()) {
    for (const char* key : {"u_heights", "w_heights"}) {
      if (preset["grid"].contains(key)) {
        add_numbers(out, preset["grid"][key], root / "grid" / key, std::string("grid.") + key, heights, model_size);
      }
    }
  }
  if (preset.contains("row") && preset["row"].is_object() && preset["row"].contains("free_heights")) {
    add_numbers(out, preset["row"]["free_heights"], root / "row" / "free_heights", "row.free_heights", heights, model_size);
  }
  if (preset.contains("couplings") && preset["couplings"].is_array()) {
    const json& list = preset["couplings"];
    for (std::size_t k = 0; k < list.size(); ++k) {
      if (!list[k].is_object()) continue;
      const std::string name = "couplings[" + std::to_string(k) + "]";
      if (list[k].contains("free_heights")) {
        add_numbers(out, list[k]["free_heights"], root / "couplings" / k / "free_heights", name + ".free_heights", heights, model_size);
      }
      if (list[k].contains("free_height") && list[k]["free_height"].is_number()) {
        out.push_back({name + ".free_height", root / "couplings" / k / "free_height", heights, std::nullopt, model_size});
      }
    }
  }
  const auto trajectory = DesignField::Group::trajectory;
  if (preset.contains("trajectory")) {
    const json& t = preset["trajectory"];
    if (t.is_array()) {
      add_points(out, t, root / "trajectory", "trajectory", trajectory, model_size, true);
    } else if (t.is_object() && t.contains("spline") && t["spline"].is_object() && t["spline"].contains("control_points")) {
      add_points(out, t["spline"]["control_points"], root / "trajectory" / "spline" / "control_points",
                 "trajectory.spline.control_points", trajectory, model_size, false);
    } else if (t.is_object() && t.contains("helix") && t["helix"].is_object()) {
      const json& h = t["helix"];
      for (const char* key : {"radius", "rise_per_turn"}) {
        if (h.contains(key) && h[key].is_number()) {
          out.push_back({std::string("trajectory.helix.") + key, root / "trajectory" / "helix" / key, trajectory, std::nullopt, model_size});
        }
      }
    }
  }
  if (preset.contains("directions") && preset["directions"].is_array()) {
    add_points(out, preset["directions"], root / "directions", "directions", DesignField::Group::directions, model_size, true);
  }
  return out;
}

std::vector<std::vector<FieldHint>> field_hints(const json& preset, const Design& design,
                                                const std::vector<MemberFace>& faces, const std::vector<HintGoal>& given) {
  std::vector<HintGoal> goals = given;
  goals.resize(faces.size());
  const Assembly& a = design.assembly;
  const double size = bounded_model_size(design), size2 = size * size;
  std::vector<Vec3> normals;
  std::vector<std::array<double, 4>> at_star;
  std::vector<std::size_t> strips;
  for (const MemberFace& f : faces) {
    const PanelNets nets = panel_nets(a, f.member, f.local);
    normals.push_back(quad_normal(nets.general));
    at_star.push_back(measure(a, f, goals[at_star.size()], normals.back(), size2));
    strips.push_back(nets.row);
  }
  struct Best {
    double cost = std::numeric_limits<double>::infinity();
    FieldHint hint;
  };
  // Per face and field group: the smallest change (relative to the field's scale).
  std::vector<std::array<Best, 3>> best(faces.size());
  for (const DesignField& field : design_fields(preset, size)) {
    std::vector<std::size_t> affected;
    for (std::size_t k = 0; k < faces.size(); ++k) {
      // A face of strip i lies between profiles i and i + 1: trajectory points and
      // directions i - 1 .. i + 2 shape it most directly.
      if (!field.row || (*field.row + 1 >= strips[k] && *field.row <= strips[k] + 2)) affected.push_back(k);
    }
    if (affected.empty()) continue;
    const double value = preset.at(field.pointer).get<double>();
    const double h = 1e-6 * std::max(std::abs(value), field.scale);
    std::array<std::vector<std::array<double, 4>>, 2> sides;
    bool built = true;
    for (int side = 0; side < 2 && built; ++side) {
      json changed = preset;
      changed.at(field.pointer) = value + (side == 0 ? h : -h);
      try {
        const Design d = design_from_json(changed);
        for (std::size_t k : affected) {
          if (faces[k].member >= d.assembly.member_count() ||
              d.assembly.topology(faces[k].member).face_count() != a.topology(faces[k].member).face_count()) {
            built = false;
            break;
          }
          sides[side].push_back(measure(d.assembly, faces[k], goals[k], normals[k], size2));
        }
      } catch (const Error&) {
        built = false;  // the change breaks an assumption (or a smooth curve's chord count changes)
      }
    }
    if (!built) continue;
    for (std::size_t e = 0; e < affected.size(); ++e) {
      const std::size_t k = affected[e];
      for (int c = 0; c < 4; ++c) {
        const double slope = (sides[0][e][c] - sides[1][e][c]) / (2.0 * h);
        if (!(std::abs(slope) > 1e-12)) continue;
        const double change = -at_star[k][c] / slope;
        const double cost = std::abs(change) / field.scale;
        Best& b = best[k][static_cast<int>(field.group)];
        if (std::isfinite(change) && cost < b.cost) b = {cost, {field.name, value, change}};
      }
    }
  }
  std::vector<std::vector<FieldHint>> out(faces.size());
  for (std::size_t k = 0; k < faces.size(); ++k) {
    std::array<Best, 3> b = best[k];
    std::sort(b.begin(), b.end(), [](const Best& x, const Best& y) { return x.cost < y.cost; });
    for (int g = 0; g < 2; ++g) {
      if (std::isfinite(b[g].cost)) out[k].push_back(b[g].hint);
    }
  }
  return out;
}

std::vector<FieldHint> collision_hints(const json& preset, const Design& design, const Collision& collision) {
  const double margin = collision_margin_at_t_star(design, collision);
  if (!std::isfinite(margin)) return {};
  const double goal = collision.kind == Collision::Kind::hinge ? collision_hint_opening : 0.0;
  const std::size_t faces = panel_mesh(design).faces.size();
  struct Best {
    double cost = std::numeric_limits<double>::infinity();
    FieldHint hint;
  };
  std::array<Best, 3> best;
  for (const DesignField& field : design_fields(preset, bounded_model_size(design))) {
    const double value = preset.at(field.pointer).get<double>();
    const double h = 1e-6 * std::max(std::abs(value), field.scale);
    for (const double step : {h, -h}) {
      json changed = preset;
      changed.at(field.pointer) = value + step;
      double moved = 0.0;
      try {
        const Design d = design_from_json(changed);
        if (panel_mesh(d).faces.size() != faces) continue;
        moved = collision_margin_at_t_star(d, collision);
      } catch (const Error&) {
        continue;  // the change breaks an assumption
      }
      const double gain = (moved - margin) / std::abs(step);  // per unit of change this way
      if (!(gain > 1e-12) || !std::isfinite(gain)) continue;
      const double change = (step > 0.0 ? 1.0 : -1.0) * (goal - margin) / gain;
      const double cost = std::abs(change) / field.scale;
      Best& b = best[static_cast<int>(field.group)];
      // Beyond the field's own scale (the model size, a direction's length) a
      // first-order change says nothing: no hint.
      if (std::isfinite(change) && cost <= 1.0 && cost < b.cost) b = {cost, {field.name, value, change}};
    }
  }
  std::sort(best.begin(), best.end(), [](const Best& x, const Best& y) { return x.cost < y.cost; });
  std::vector<FieldHint> out;
  for (int g = 0; g < 2; ++g) {
    if (std::isfinite(best[g].cost)) out.push_back(best[g].hint);
  }
  return out;
}

}  // namespace phedra
