#include "phedra/design_variables.h"

#include "phedra/errors.h"

#include <algorithm>
#include <cmath>

namespace phedra {
namespace {

using json = nlohmann::json;
using Pointer = json::json_pointer;

bool is_number_array(const json& j) {
  if (!j.is_array() || j.empty()) return false;
  for (const json& v : j) {
    if (!v.is_number()) return false;
  }
  return true;
}

}  // namespace

std::string to_string(VariableGroup group) {
  switch (group) {
    case VariableGroup::apex_heights: return "apex_heights";
    case VariableGroup::directions: return "directions";
    case VariableGroup::trajectory: return "trajectory";
  }
  return "?";
}

std::vector<VariableGroup> parse_variable_groups(const std::string& list) {
  std::vector<VariableGroup> out;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t end = std::min(list.find(',', start), list.size());
    const std::string name = list.substr(start, end - start);
    if (name == "apex_heights") {
      out.push_back(VariableGroup::apex_heights);
    } else if (name == "directions") {
      out.push_back(VariableGroup::directions);
    } else if (name == "trajectory") {
      out.push_back(VariableGroup::trajectory);
    } else {
      throw InvalidInputError("--vary", "unknown group \"" + name +
                                            "\" (a comma-separated list of apex_heights, directions, trajectory)");
    }
    start = end + 1;
  }
  return out;
}

void DesignVariables::add_length(const Pointer& pointer, const std::string& field, double model_size) {
  slot_.push_back(lengths_.size());
  lengths_.push_back({pointer});
  variables_.push_back({field, DesignVariable::Kind::length, preset_.at(pointer).get<double>(), model_size, false, ""});
}

DesignVariables::DesignVariables(const json& preset, const std::vector<VariableGroup>& groups, double model_size,
                                 const std::vector<std::string>& fixed)
    : preset_(preset) {
  const Pointer root;
  if (preset_.contains("axis") && is_number_array(preset_["axis"]) && preset_["axis"].size() == 3) {
    axis_ = preset_["axis"].get<std::vector<double>>();
    const double n = std::sqrt(axis_[0] * axis_[0] + axis_[1] * axis_[1] + axis_[2] * axis_[2]);
    if (n > 0.0) {
      for (double& c : axis_) c /= n;
    }
  }
  auto list = [&](const Pointer& at, const std::string& name, std::size_t count) {
    for (std::size_t k = 0; k < count; ++k) add_length(at / k, name + "[" + std::to_string(k) + "]", model_size);
  };
  for (const VariableGroup group : groups) {
    if (group == VariableGroup::apex_heights) {
      if (is_number_array(preset_.value("apex_heights", json()))) {
        const json& h = preset_["apex_heights"];
        const std::size_t n = h.size();
        // A core-schema tube repeats its first two heights at the end: keep it closed.
        if (n >= 6 && h[n - 2] == h[0] && h[n - 1] == h[1]) {
          const std::size_t first = variables_.size();
          // An anti-parallelogram one (n = 6, every sign '-') keeps z3 = z0 + z2 - z1 too.
          const json signs = preset_.value("signs", json());
          const bool anti = n == 6 && signs.is_string() && signs.get<std::string>().find('+') == std::string::npos;
          list(root / "apex_heights", "apex_heights", anti ? 3 : n - 2);
          if (anti) ties_.push_back({root / "apex_heights" / 3, {{first, 1.0}, {first + 2, 1.0}, {first + 1, -1.0}}});
          ties_.push_back({root / "apex_heights" / (n - 2), {{first, 1.0}}});
          ties_.push_back({root / "apex_heights" / (n - 1), {{first + 1, 1.0}}});
        } else {
          list(root / "apex_heights", "apex_heights", n);
        }
      }
      if (preset_.contains("tube") && preset_["tube"].is_object() && is_number_array(preset_["tube"].value("apex_heights", json()))) {
        const json& tube = preset_["tube"];
        const std::size_t first = variables_.size();
        if (tube.value("type", "") == "anti-parallelogram" && tube["apex_heights"].size() == 4) {
          // Its symmetry condition z3 = z0 + z2 - z1 keeps it closed.
          list(root / "tube" / "apex_heights", "tube.apex_heights", 3);
          ties_.push_back({root / "tube" / "apex_heights" / 3, {{first, 1.0}, {first + 2, 1.0}, {first + 1, -1.0}}});
        } else {
          list(root / "tube" / "apex_heights", "tube.apex_heights", tube["apex_heights"].size());
        }
      }
      if (preset_.contains("grid") && preset_["grid"].is_object()) {
        for (const char* key : {"u_heights", "w_heights"}) {
          if (is_number_array(preset_["grid"].value(key, json()))) {
            list(root / "grid" / key, std::string("grid.") + key, preset_["grid"][key].size());
          }
        }
      }
      if (preset_.contains("row") && preset_["row"].is_object() && is_number_array(preset_["row"].value("free_heights", json()))) {
        list(root / "row" / "free_heights", "row.free_heights", preset_["row"]["free_heights"].size());
      }
      if (preset_.contains("couplings") && preset_["couplings"].is_array()) {
        for (std::size_t c = 0; c < preset_["couplings"].size(); ++c) {
          const json& coupling = preset_["couplings"][c];
          if (!coupling.is_object()) continue;
          const std::string name = "couplings[" + std::to_string(c) + "]";
          if (is_number_array(coupling.value("free_heights", json()))) {
            list(root / "couplings" / c / "free_heights", name + ".free_heights", coupling["free_heights"].size());
          }
          if (coupling.contains("free_height") && coupling["free_height"].is_number()) {
            add_length(root / "couplings" / c / "free_height", name + ".free_height", model_size);
          }
        }
      }
    } else if (group == VariableGroup::directions) {
      const json& d = preset_.value("directions", json());
      if (d.is_array()) {
        for (std::size_t i = 0; i < d.size(); ++i) {
          if (!is_number_array(d[i]) || d[i].size() != 3) continue;
          slot_.push_back(turns_.size());
          turns_.push_back({root / "directions" / i, d[i].get<std::vector<double>>()});
          variables_.push_back({"directions[" + std::to_string(i) + "]", DesignVariable::Kind::turn, 0.0, 1.0, false, ""});
        }
      } else {
        notes_.push_back("directions are given by a rule: not varied (write them out as vectors to vary them)");
      }
    } else {
      const json& t = preset_.value("trajectory", json());
      if (t.is_array()) {
        for (std::size_t i = 0; i < t.size(); ++i) {
          if (is_number_array(t[i])) list(root / "trajectory" / i, "trajectory[" + std::to_string(i) + "]", t[i].size());
        }
      } else if (t.is_object() && t.contains("spline") && t["spline"].is_object()) {
        const json& points = t["spline"].value("control_points", json());
        for (std::size_t i = 0; i < points.size(); ++i) {
          if (is_number_array(points[i])) {
            list(root / "trajectory" / "spline" / "control_points" / i,
                 "trajectory.spline.control_points[" + std::to_string(i) + "]", points[i].size());
          }
        }
      } else if (t.is_object() && t.contains("helix") && t["helix"].is_object()) {
        for (const char* key : {"radius", "rise_per_turn"}) {
          if (t["helix"].contains(key) && t["helix"][key].is_number()) {
            add_length(root / "trajectory" / "helix" / key, std::string("trajectory.helix.") + key, model_size);
          }
        }
      }
    }
  }
  // A held field stays (a trajectory point or direction: all its coordinates).
  for (std::size_t k = 0; k < variables_.size(); ++k) {
    const bool turn = variables_[k].kind == DesignVariable::Kind::turn;
    const std::string pointer = turn ? turns_[slot_[k]].pointer.to_string() : lengths_[slot_[k]].pointer.to_string();
    variables_[k].pointer = pointer;
    for (const std::string& f : fixed) {
      if (pointer == f || pointer.rfind(f + "/", 0) == 0) variables_[k].fixed = true;
    }
  }
  if (variables_.empty()) {
    std::string why;
    for (const std::string& note : notes_) why += "; " + note;
    throw InvalidInputError("--vary", "nothing to change: the preset has no numbers in the groups asked for" + why);
  }
}

std::vector<double> DesignVariables::start() const {
  std::vector<double> x;
  x.reserve(variables_.size());
  for (const DesignVariable& v : variables_) x.push_back(v.start);
  return x;
}

json DesignVariables::preset_at(const std::vector<double>& x) const {
  json p = preset_;
  for (std::size_t k = 0; k < variables_.size(); ++k) {
    if (x[k] == variables_[k].start) continue;
    if (variables_[k].kind == DesignVariable::Kind::length) {
      p.at(lengths_[slot_[k]].pointer) = x[k];
      continue;
    }
    // Turn the direction about the axis by x[k] radians: d cos + (a x d) sin (d is orthogonal to a).
    const Turn& turn = turns_[slot_[k]];
    const std::vector<double>& d = turn.direction;
    const std::vector<double>& a = axis_;
    const double c = std::cos(x[k]), s = std::sin(x[k]);
    const double cross[3] = {a[1] * d[2] - a[2] * d[1], a[2] * d[0] - a[0] * d[2], a[0] * d[1] - a[1] * d[0]};
    p.at(turn.pointer) = json::array({c * d[0] + s * cross[0], c * d[1] + s * cross[1], c * d[2] + s * cross[2]});
  }
  for (const Tie& tie : ties_) {
    if (std::none_of(tie.terms.begin(), tie.terms.end(), [&](const auto& term) { return x[term.first] != variables_[term.first].start; })) {
      continue;
    }
    double value = 0.0;
    for (const auto& [k, coefficient] : tie.terms) value += coefficient * x[k];
    p.at(tie.target) = value;
  }
  return p;
}

std::vector<double> DesignVariables::values_of(const json& other, const std::string& field) const {
  std::vector<double> x(variables_.size());
  for (std::size_t k = 0; k < variables_.size(); ++k) {
    const DesignVariable& v = variables_[k];
    const Pointer at(v.pointer);
    const bool turn = v.kind == DesignVariable::Kind::turn;
    if (!other.contains(at) || (turn ? !is_number_array(other.at(at)) || other.at(at).size() != 3 : !other.at(at).is_number())) {
      throw InvalidInputError(field, "its designs have no " + v.field + (turn ? " (a direction vector)" : " (a number)") +
                                         " as the preset has: not variations of it");
    }
    if (!turn) {
      x[k] = other.at(at).get<double>();
      continue;
    }
    // The turn about the axis from the input's direction d to e: atan2((a x d) . e, d . e).
    const std::vector<double>& d = turns_[slot_[k]].direction;
    const std::vector<double> e = other.at(at).get<std::vector<double>>();
    const std::vector<double>& a = axis_;
    const double cross[3] = {a[1] * d[2] - a[2] * d[1], a[2] * d[0] - a[0] * d[2], a[0] * d[1] - a[1] * d[0]};
    x[k] = std::atan2(cross[0] * e[0] + cross[1] * e[1] + cross[2] * e[2], d[0] * e[0] + d[1] * e[1] + d[2] * e[2]);
  }
  return x;
}

std::vector<std::pair<std::string, std::string>> DesignVariables::tied_fields() const {
  std::vector<std::pair<std::string, std::string>> out;
  for (const Tie& tie : ties_) {
    std::string rule;
    for (const auto& [k, coefficient] : tie.terms) {
      rule += (rule.empty() ? (coefficient < 0.0 ? "-" : "") : (coefficient < 0.0 ? " - " : " + ")) + variables_[k].field;
    }
    out.emplace_back(tie.target.to_string(), rule);
  }
  return out;
}

double DesignVariables::distance(const std::vector<double>& x) const {
  double sum = 0.0;
  for (std::size_t k = 0; k < variables_.size(); ++k) {
    const double d = (x[k] - variables_[k].start) / variables_[k].scale;
    sum += d * d;
  }
  return std::sqrt(sum);
}

}  // namespace phedra
