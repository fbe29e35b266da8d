#pragma once
// A preset's numeric fields by their paths, as users write them (the atlas's
// parameters, docs/atlas.md): "apex_heights[3]", "grid.u_heights[1]",
// "trajectory[4][1]" (a point's coordinate), "directions[2].turn" (a profile
// direction's turn about the axis, in degrees, staying orthogonal to it), or any
// other number of the preset ("trajectory.helix.radius", "couplings[0].free_height").
// Setting a height keeps a tube closed as a repair does (DesignVariables): a
// core-schema tube's repeated heights and an anti-parallelogram tube's symmetry
// follow their free heights, and are refused as parameters themselves.

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

namespace phedra {

/// Checks `path` names a number of `preset` that can be set; its value there
/// (0 for a turn). InvalidInputError(field_name, ...) naming the path otherwise.
double preset_field_value(const nlohmann::json& preset, const std::string& path, const std::string& field_name);

/// The preset with each (path, value) set (and the values tied to them following).
nlohmann::json preset_with_fields(const nlohmann::json& preset,
                                  const std::vector<std::pair<std::string, double>>& values);

}  // namespace phedra
