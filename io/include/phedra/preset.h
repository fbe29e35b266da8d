#pragma once
// Reading and writing presets (JSON, schema in presets/preset.schema.json,
// documented in docs/presets.md). Parsing checks types and shapes only; the
// geometric assumptions are checked by validate() and the PHedron constructor.

#include "phedra/control_polylines.h"
#include "phedra/json_fields.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string_view>

namespace phedra {

/// Keys a wider preset (tubes, couplings) adds to the core schema.
struct PresetKeys {
  /// Further keys the caller handles; the core ignores them.
  std::vector<std::string> extra;
  /// Whether `apex_heights` and `signs` are required (a tube or grid key may set them).
  bool require_profile = true;
};

/// Control polylines from a parsed preset object. Throws InvalidInputError naming
/// the field (for example "trajectory[2][1]") for a missing key, an unknown key,
/// a wrong type, a wrong shape or a non-finite number.
ControlPolylines preset_from_json(const nlohmann::json& preset, const PresetKeys& keys = {});

/// The preset object of a document: the document itself, or its "preset" member
/// for a reference case file.
const nlohmann::json& preset_object(const nlohmann::json& document);

/// Parses preset text: a preset object, or a reference case file whose preset
/// sits under the key "preset". Malformed JSON throws InvalidInputError with the
/// line and column of the problem.
ControlPolylines parse_preset(std::string_view text);

/// Reads and parses a preset file (IOError when it cannot be read).
ControlPolylines load_preset(const std::filesystem::path& path);

/// The preset object of `input` (round-trips through preset_from_json).
nlohmann::json preset_to_json(const ControlPolylines& input);

}  // namespace phedra
