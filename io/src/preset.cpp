#include "phedra/preset.h"

#include "phedra/curve_preset.h"
#include "phedra/errors.h"
#include "phedra/files.h"
#include "phedra/json_fields.h"
#include "phedra/number_format.h"

#include <algorithm>

namespace phedra {
namespace {

using nlohmann::json;


const json& required(const json& preset, const char* key) {
  auto it = preset.find(key);
  if (it == preset.end()) throw InvalidInputError(key, "missing (required key)");
  return *it;
}

const std::vector<std::string>& core_keys() {
  static const std::vector<std::string> keys{"$schema",    "name", "description",  "trajectory",
                                             "directions", "axis", "apex_heights", "signs"};
  return keys;
}

}  // namespace

ControlPolylines preset_from_json(const json& preset, const PresetKeys& keys) {
  if (!preset.is_object()) throw InvalidInputError("", "a preset must be a JSON object, got " + std::string(preset.type_name()));
  std::vector<std::string> known = core_keys();
  known.insert(known.end(), keys.extra.begin(), keys.extra.end());
  for (const auto& [key, value] : preset.items()) {
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      std::string list;
      for (std::size_t k = 1; k < known.size(); ++k) list += (k > 1 ? ", " : "") + known[k];
      throw InvalidInputError(key, "unknown key (known: " + list + ")");
    }
  }
  ControlPolylines input;
  if (auto it = preset.find("name"); it != preset.end()) {
    if (!it->is_string()) throw InvalidInputError("name", "expected a string, got " + std::string(it->type_name()));
    input.name = it->get<std::string>();
  }
  if (auto it = preset.find("axis"); it != preset.end()) input.axis = json_vector(*it, "axis");
  // The curves and rules need a usable axis (validate() checks it is a unit vector).
  const Vec3 axis = input.axis.norm() > 0.0 ? input.axis : Vec3::UnitZ();
  const json& trajectory = required(preset, "trajectory");
  const json& directions = required(preset, "directions");
  Points tangents;
  if (trajectory.is_object()) {
    CurveSampling curve = trajectory_curve(trajectory, axis);
    input.trajectory = std::move(curve.points);
    tangents = std::move(curve.tangents);
    input.trajectory_source = curve.kind + ", " + std::to_string(input.trajectory.size() - 1) +
                              " segments, largest chord deviation " + format_number(curve.deviation) +
                              " (tolerance " + format_number(curve.tolerance) + ")";
    if (directions.is_array()) {
      throw InvalidInputError("directions", "a smooth trajectory needs a direction rule ({\"rule\": \"normal\"} or "
                                            "{\"rule\": \"radial\", \"through\": [x, y, z]}): its point count is "
                                            "not known in advance");
    }
  } else {
    input.trajectory = json_points(trajectory, "trajectory");
  }
  input.directions = directions.is_object() ? directions_by_rule(directions, input.trajectory, tangents, axis)
                                            : json_points(directions, "directions");
  if (keys.require_profile || preset.contains("apex_heights")) {
    input.apex_heights = json_numbers(required(preset, "apex_heights"), "apex_heights");
  }
  if (keys.require_profile || preset.contains("signs")) {
    const json& signs = required(preset, "signs");
    if (!signs.is_string()) {
      throw InvalidInputError("signs", "expected a string of '+' and '-', got " + std::string(signs.type_name()));
    }
    input.signs = signs_from_string(signs.get<std::string>());
  }
  return input;
}

const json& preset_object(const json& document) {
  // A reference case file ({"preset": {...}, "expected": {...}}) holds its preset under "preset".
  if (document.is_object() && document.contains("preset") && !document.contains("trajectory")) {
    return document["preset"];
  }
  return document;
}

ControlPolylines parse_preset(std::string_view text) { return preset_from_json(preset_object(parse_json_text(text))); }

ControlPolylines load_preset(const std::filesystem::path& path) { return parse_preset(read_text_file(path)); }

json preset_to_json(const ControlPolylines& input) {
  auto points = [](const Points& ps) {
    json a = json::array();
    for (const Vec3& p : ps) a.push_back({p.x(), p.y(), p.z()});
    return a;
  };
  return json{{"name", input.name},
              {"trajectory", points(input.trajectory)},
              {"directions", points(input.directions)},
              {"axis", {input.axis.x(), input.axis.y(), input.axis.z()}},
              {"apex_heights", input.apex_heights},
              {"signs", signs_to_string(input.signs)}};
}

}  // namespace phedra
