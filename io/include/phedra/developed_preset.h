#pragma once
// The developed (flat) pattern file (docs/presets.md, "Developed patterns").

#include "phedra/developed_pattern.h"

#include <nlohmann/json.hpp>

namespace phedra {

/// From {"name", "developed": {"trajectory": [[x, z], ...], "apex_heights": [...], "signs": "..."}}.
/// InvalidInputError naming the field (e.g. "developed.trajectory[2]").
DevelopedInput developed_from_json(const nlohmann::json& document);

}  // namespace phedra
