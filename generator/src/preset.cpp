#include "phedra/preset.h"

#include "phedra/number_format.h"
#include "phedra/smooth_trajectory.h"

#include "phedra/errors.h"

#include <cmath>
#include <fstream>
#include <algorithm>
#include <sstream>

namespace phedra {
namespace {

using nlohmann::json;

std::string type_name(const json& value) { return value.type_name(); }

}  // namespace

using nlohmann::json;

double json_number(const json& value, const std::string& field) {
  if (!value.is_number()) {
    throw InvalidInputError(field, "expected a number, got " + type_name(value));
  }
  const double x = value.get<double>();
  if (!std::isfinite(x)) throw InvalidInputError(field, "is not a finite number");
  return x;
}

std::size_t json_index(const json& value, const std::string& field) {
  if (!value.is_number_integer() || value.get<long long>() < 0) {
    throw InvalidInputError(field, "expected a non-negative integer, got " + value.dump());
  }
  return value.get<std::size_t>();
}

std::vector<double> json_numbers(const json& value, const std::string& field) {
  if (!value.is_array()) throw InvalidInputError(field, "expected an array of numbers, got " + type_name(value));
  std::vector<double> numbers;
  numbers.reserve(value.size());
  for (std::size_t i = 0; i < value.size(); ++i) {
    numbers.push_back(json_number(value[i], field + "[" + std::to_string(i) + "]"));
  }
  return numbers;
}

namespace {

Vec3 read_vector(const json& value, const std::string& field) {
  if (!value.is_array() || value.size() != 3) {
    throw InvalidInputError(field, "expected an array of 3 numbers [x, y, z], got " +
                                       (value.is_array() ? "an array of " + std::to_string(value.size()) +
                                                               " elements"
                                                         : type_name(value)));
  }
  Vec3 v;
  for (int k = 0; k < 3; ++k) v[k] = json_number(value[k], field + "[" + std::to_string(k) + "]");
  return v;
}

Points read_points(const json& value, const std::string& field) {
  if (!value.is_array()) throw InvalidInputError(field, "expected an array of [x, y, z], got " + type_name(value));
  Points points;
  points.reserve(value.size());
  for (std::size_t i = 0; i < value.size(); ++i) {
    points.push_back(read_vector(value[i], field + "[" + std::to_string(i) + "]"));
  }
  return points;
}

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

std::pair<std::size_t, std::size_t> line_and_column(std::string_view text, std::size_t byte) {
  std::size_t line = 1, column = 1;
  for (std::size_t k = 0; k < byte && k < text.size(); ++k) {
    if (text[k] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

}  // namespace

ControlPolylines preset_from_json(const json& preset, const PresetKeys& keys) {
  if (!preset.is_object()) throw InvalidInputError("", "a preset must be a JSON object, got " + type_name(preset));
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
    if (!it->is_string()) throw InvalidInputError("name", "expected a string, got " + type_name(*it));
    input.name = it->get<std::string>();
  }
  if (auto it = preset.find("axis"); it != preset.end()) input.axis = read_vector(*it, "axis");
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
    input.trajectory = read_points(trajectory, "trajectory");
  }
  input.directions = directions.is_object() ? directions_by_rule(directions, input.trajectory, tangents, axis)
                                            : read_points(directions, "directions");
  if (keys.require_profile || preset.contains("apex_heights")) {
    input.apex_heights = json_numbers(required(preset, "apex_heights"), "apex_heights");
  }
  if (keys.require_profile || preset.contains("signs")) {
    const json& signs = required(preset, "signs");
    if (!signs.is_string()) {
      throw InvalidInputError("signs", "expected a string of '+' and '-', got " + type_name(signs));
    }
    input.signs = signs_from_string(signs.get<std::string>());
  }
  return input;
}

json parse_json_text(std::string_view text) {
  if (text.substr(0, 4) == "glTF") {
    throw InvalidInputError("", "this is a binary glTF file (.glb), not a JSON preset: `phedra view FILE.glb` shows it");
  }
  try {
    return json::parse(text.begin(), text.end());
  } catch (const json::parse_error& e) {
    // e.byte is 1-based and points just past the offending character.
    const std::size_t at = e.byte == 0 ? 0 : e.byte - 1;
    auto [line, column] = line_and_column(text, at);
    std::string what = e.what();
    if (auto pos = what.find("syntax error"); pos != std::string::npos) what = what.substr(pos);
    throw InvalidInputError("", "malformed JSON at line " + std::to_string(line) + ", column " +
                                    std::to_string(column) + ": " + what);
  } catch (const json::out_of_range& e) {
    // A number too large for a double ("number overflow parsing '1e999'"): locate it.
    std::string what = e.what();
    std::string where;
    if (auto open = what.find('\''), close = what.rfind('\''); open != std::string::npos && close > open) {
      if (auto at = text.find(what.substr(open + 1, close - open - 1)); at != std::string_view::npos) {
        auto [line, column] = line_and_column(text, at);
        where = " at line " + std::to_string(line) + ", column " + std::to_string(column);
      }
    }
    if (auto pos = what.find("number overflow"); pos != std::string::npos) what = what.substr(pos);
    throw InvalidInputError("", "not a finite number" + where + ": " + what);
  }
}

const json& preset_object(const json& document) {
  // A reference case file ({"preset": {...}, "expected": {...}}) holds its preset under "preset".
  if (document.is_object() && document.contains("preset") && !document.contains("trajectory")) {
    return document["preset"];
  }
  return document;
}

ControlPolylines parse_preset(std::string_view text) { return preset_from_json(preset_object(parse_json_text(text))); }

std::string read_text_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw IOError(path.string() + ": is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IOError(path.string() + ": cannot open for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw IOError(path.string() + ": read error");
  return buffer.str();
}

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
