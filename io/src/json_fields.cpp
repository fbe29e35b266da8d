#include "phedra/json_fields.h"

#include "phedra/errors.h"

#include <algorithm>
#include <cmath>

namespace phedra {
namespace {

using nlohmann::json;

std::string type_name(const json& value) { return value.type_name(); }

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

Vec3 json_vector(const json& value, const std::string& field) {
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

Points json_points(const json& value, const std::string& field) {
  if (!value.is_array()) throw InvalidInputError(field, "expected an array of [x, y, z], got " + type_name(value));
  Points points;
  points.reserve(value.size());
  for (std::size_t i = 0; i < value.size(); ++i) {
    points.push_back(json_vector(value[i], field + "[" + std::to_string(i) + "]"));
  }
  return points;
}

bool json_boolean(const json& value, const std::string& field) {
  if (!value.is_boolean()) throw InvalidInputError(field, "expected true or false, got " + type_name(value));
  return value.get<bool>();
}

const json& json_member(const json& object, const std::string& field, const char* key) {
  auto it = object.find(key);
  if (it == object.end()) throw InvalidInputError(field + "." + key, "missing (required key)");
  return *it;
}

void json_only_keys(const json& object, const std::string& field, const std::vector<std::string>& known) {
  if (!object.is_object()) throw InvalidInputError(field, "expected an object, got " + type_name(object));
  for (const auto& [key, value] : object.items()) {
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      throw InvalidInputError(field + "." + key, "unknown key (known: " + list + ")");
    }
  }
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

}  // namespace phedra
