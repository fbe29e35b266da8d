#pragma once
// Reading the fields of a JSON document (presets, developed patterns), each
// failure an InvalidInputError naming the field as a user writes it
// ("trajectory[2][1]", "grid.u_heights", "trajectory.helix.radius").

#include "phedra/vector_types.h"

#include <nlohmann/json.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace phedra {

/// A finite number.
double json_number(const nlohmann::json& value, const std::string& field);
/// An array of finite numbers.
std::vector<double> json_numbers(const nlohmann::json& value, const std::string& field);
/// A non-negative integer.
std::size_t json_index(const nlohmann::json& value, const std::string& field);
/// [x, y, z] of finite numbers.
Vec3 json_vector(const nlohmann::json& value, const std::string& field);
/// An array of [x, y, z].
Points json_points(const nlohmann::json& value, const std::string& field);
/// true or false.
bool json_boolean(const nlohmann::json& value, const std::string& field);
/// The member `key` of `object` (InvalidInputError "FIELD.KEY: missing (required key)").
const nlohmann::json& json_member(const nlohmann::json& object, const std::string& field, const char* key);
/// Refuses an object with a key outside `known` ("FIELD.KEY: unknown key (known: ...)"), or a value that is not an object.
void json_only_keys(const nlohmann::json& object, const std::string& field, const std::vector<std::string>& known);

/// Parses JSON text; a syntax error becomes InvalidInputError("", "malformed JSON at line L, column C: ...").
nlohmann::json parse_json_text(std::string_view text);

}  // namespace phedra
