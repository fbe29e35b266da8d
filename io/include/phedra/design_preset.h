#pragma once
// Reading a preset (docs/presets.md) as a Design: the core keys, and `tube`,
// `grid`, `row`, `couplings` and `merge`. Other documents phedra reads or writes
// (a developed pattern, a motion JSON, glTF, FOLD) are named, not refused key by key.

#include "phedra/design.h"

#include <nlohmann/json.hpp>

#include <filesystem>

namespace phedra {

/// From a parsed preset (or reference case) document. InvalidInputError naming the
/// field for every problem.
Design design_from_json(const nlohmann::json& document);

/// Reads, parses and builds a preset file (IOError when unreadable).
Design load_design(const std::filesystem::path& path);

}  // namespace phedra
