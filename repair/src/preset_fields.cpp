#include "phedra/preset_fields.h"

#include "phedra/design_variables.h"
#include "phedra/errors.h"

#include <cctype>
#include <cmath>
#include <numbers>
#include <optional>

namespace phedra {
namespace {

using json = nlohmann::json;
using Pointer = json::json_pointer;

const char* const turn_suffix = ".turn";

bool is_turn(const std::string& path) {
  const std::size_t n = std::string(turn_suffix).size();
  return path.size() > n && path.compare(path.size() - n, n, turn_suffix) == 0;
}

/// "grid.u_heights[1]" -> /grid/u_heights/1; InvalidInputError for a malformed path.
Pointer pointer_of(const std::string& path, const std::string& field_name) {
  Pointer p;
  std::size_t i = 0;
  auto bad = [&](const std::string& why) {
    return InvalidInputError(field_name, "\"" + path + "\" is not a field path (" + why +
                                             "; write it as in grid.u_heights[1], trajectory[4][0], directions[2].turn)");
  };
  if (path.empty()) throw bad("it is empty");
  while (i < path.size()) {
    if (path[i] == '[') {
      const std::size_t close = path.find(']', i);
      if (close == std::string::npos || close == i + 1) throw bad("a '[' without an index and ']'");
      const std::string index = path.substr(i + 1, close - i - 1);
      for (char c : index) {
        if (!std::isdigit(static_cast<unsigned char>(c))) throw bad("the index \"" + index + "\" is not a whole number");
      }
      p /= std::stoul(index);
      i = close + 1;
      if (i < path.size() && path[i] == '.') {
        ++i;
        if (i == path.size()) throw bad("it ends with '.'");
      }
      continue;
    }
    std::size_t end = i;
    while (end < path.size() && path[end] != '.' && path[end] != '[') ++end;
    if (end == i) throw bad("an empty name");
    p /= path.substr(i, end - i);
    i = end;
    if (i < path.size() && path[i] == '.') {
      ++i;
      if (i == path.size()) throw bad("it ends with '.'");
    }
  }
  return p;
}

std::optional<std::size_t> variable_named(const DesignVariables& v, const std::string& field) {
  for (std::size_t k = 0; k < v.size(); ++k) {
    if (v.variables()[k].field == field) return k;
  }
  return std::nullopt;
}

std::optional<DesignVariables> variables_of(const json& preset) {
  try {
    return DesignVariables(preset, {VariableGroup::apex_heights, VariableGroup::directions, VariableGroup::trajectory}, 1.0);
  } catch (const InvalidInputError&) {
    return std::nullopt;  // nothing a repair would vary: every field is set as it stands
  }
}

const char* type_name(const json& j) {
  if (j.is_array()) return "a list";
  if (j.is_object()) return "an object";
  if (j.is_string()) return "text";
  if (j.is_boolean()) return "true or false";
  if (j.is_null()) return "null";
  return "a number";
}

/// The checks of preset_field_value with the variables already made.
double field_value(const json& preset, const std::optional<DesignVariables>& vars, const std::string& path,
                   const std::string& field_name) {
  if (is_turn(path)) {
    const std::string direction = path.substr(0, path.size() - std::string(turn_suffix).size());
    if (vars && variable_named(*vars, direction)) return 0.0;
    const json& d = preset.is_object() ? preset.value("directions", json()) : json();
    throw InvalidInputError(field_name, "\"" + path + "\": " +
                                            (d.is_array() ? "the preset's directions are directions[0] to directions[" +
                                                                std::to_string(d.size() == 0 ? 0 : d.size() - 1) + "]"
                                                          : std::string("the preset's directions are given by a rule, "
                                                                        "not as vectors: write them out to turn them")));
  }
  const Pointer p = pointer_of(path, field_name);
  if (!preset.contains(p)) throw InvalidInputError(field_name, "\"" + path + "\": the preset has no such field");
  const json& value = preset.at(p);
  if (!value.is_number()) {
    throw InvalidInputError(field_name, "\"" + path + "\" is " + type_name(value) + " in the preset, not a number" +
                                            (path.rfind("directions", 0) == 0
                                                 ? " (a direction turns: directions[k].turn, in degrees)"
                                                 : ""));
  }
  if (vars) {
    for (const auto& [pointer, rule] : vars->tied_fields()) {
      if (pointer == p.to_string()) {
        throw InvalidInputError(field_name, "\"" + path + "\" follows " + rule +
                                                " (so that the tube stays closed): make that a parameter instead");
      }
    }
  }
  return value.get<double>();
}

}  // namespace

double preset_field_value(const json& preset, const std::string& path, const std::string& field_name) {
  return field_value(preset, variables_of(preset), path, field_name);
}

json preset_with_fields(const json& preset, const std::vector<std::pair<std::string, double>>& values) {
  const std::optional<DesignVariables> vars = variables_of(preset);
  std::vector<double> x = vars ? vars->start() : std::vector<double>();
  std::vector<std::pair<Pointer, double>> direct;
  for (const auto& [path, value] : values) {
    field_value(preset, vars, path, path);
    if (!std::isfinite(value)) throw InvalidInputError(path, "\"" + path + "\": the value is not a finite number");
    if (is_turn(path)) {
      x[*variable_named(*vars, path.substr(0, path.size() - std::string(turn_suffix).size()))] =
          value * std::numbers::pi / 180.0;
      continue;
    }
    const Pointer p = pointer_of(path, path);
    bool set = false;
    if (vars) {
      for (std::size_t k = 0; k < vars->size(); ++k) {
        if (vars->variables()[k].kind == DesignVariable::Kind::length && vars->variables()[k].pointer == p.to_string()) {
          x[k] = value;
          set = true;
        }
      }
    }
    if (!set) direct.emplace_back(p, value);
  }
  json out = vars ? vars->preset_at(x) : preset;
  for (const auto& [p, value] : direct) out.at(p) = value;
  return out;
}

}  // namespace phedra
