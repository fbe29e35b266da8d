#include "phedra/developed_preset.h"

#include "phedra/errors.h"
#include "phedra/json_fields.h"

namespace phedra {
namespace {

using nlohmann::json;

std::string at(const std::string& field, std::size_t i) { return field + "[" + std::to_string(i) + "]"; }

}  // namespace

DevelopedInput developed_from_json(const json& document) {
  if (!document.is_object()) throw InvalidInputError("", "a developed pattern must be a JSON object");
  for (const auto& [key, value] : document.items()) {
    if (key != "$schema" && key != "name" && key != "description" && key != "developed") {
      throw InvalidInputError(key, "unknown key (known: name, description, developed)");
    }
  }
  auto it = document.find("developed");
  if (it == document.end() || !it->is_object()) {
    throw InvalidInputError("developed", "missing: {\"trajectory\": [[x, z], ...], \"apex_heights\": [...], \"signs\": \"...\"}");
  }
  const json& d = *it;
  for (const auto& [key, value] : d.items()) {
    if (key != "trajectory" && key != "apex_heights" && key != "signs") {
      throw InvalidInputError("developed." + key, "unknown key (known: trajectory, apex_heights, signs)");
    }
  }
  DevelopedInput in;
  if (auto name = document.find("name"); name != document.end()) {
    if (!name->is_string()) throw InvalidInputError("name", "expected a string");
    in.name = name->get<std::string>();
  }
  if (!d.contains("trajectory") || !d["trajectory"].is_array()) {
    throw InvalidInputError("developed.trajectory", "expected an array of [x, z] (distance from the axis, height)");
  }
  for (std::size_t i = 0; i < d["trajectory"].size(); ++i) {
    const std::vector<double> p = json_numbers(d["trajectory"][i], at("developed.trajectory", i));
    if (p.size() != 2) {
      throw InvalidInputError(at("developed.trajectory", i), "expected [x, z], got " + std::to_string(p.size()) + " numbers");
    }
    in.trajectory.emplace_back(p[0], p[1]);
  }
  if (!d.contains("apex_heights")) throw InvalidInputError("developed.apex_heights", "missing (required key)");
  in.apex_heights = json_numbers(d["apex_heights"], "developed.apex_heights");
  if (!d.contains("signs") || !d["signs"].is_string()) {
    throw InvalidInputError("developed.signs", "expected a string of '+' and '-'");
  }
  try {
    in.signs = signs_from_string(d["signs"].get<std::string>());
  } catch (const InvalidInputError& e) {
    throw InvalidInputError("developed.signs", e.reason());
  }
  return in;
}

}  // namespace phedra
