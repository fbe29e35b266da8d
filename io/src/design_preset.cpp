#include "phedra/design_preset.h"

#include "phedra/coupling.h"
#include "phedra/errors.h"
#include "phedra/files.h"
#include "phedra/json_fields.h"
#include "phedra/preset.h"
#include "phedra/tube_array.h"

#include <functional>
#include <optional>
#include <regex>

namespace phedra {
namespace {

using nlohmann::json;

const std::vector<std::string> design_keys{"tube", "grid", "row", "couplings", "merge"};

void forbid_profile(const json& preset, const char* key) {
  for (const char* profile : {"apex_heights", "signs"}) {
    if (preset.contains(profile)) {
      throw InvalidInputError(profile, std::string("not allowed together with \"") + key + "\", which sets the apexes");
    }
  }
}

/// Runs `build`; an error naming the generated profile's apex_heights[k] (a tube's or
/// a grid's base cell: [z0, z1, z2, z3, z0, z1]) names the preset's own field instead.
Design in_user_terms(const std::function<Design()>& build, const std::function<std::string(std::size_t)>& height) {
  try {
    return build();
  } catch (const InvalidInputError& e) {
    static const std::regex apex(R"(apex_heights\[([0-9]+)\])");
    auto rename = [&](const std::string& text) {
      std::string out;
      auto from = text.cbegin();
      for (std::sregex_iterator it(text.begin(), text.end(), apex), end; it != end; ++it) {
        out.append(from, (*it)[0].first);
        out += height(std::stoul((*it)[1].str()) % 4);
        from = (*it)[0].second;
      }
      return out.append(from, text.cend());
    };
    const std::string field = rename(e.field());
    if (field == e.field()) throw;
    throw InvalidInputError(field, rename(e.reason()));
  }
}

Design base_design(const json& preset) {
  const bool has_tube = preset.contains("tube"), has_grid = preset.contains("grid");
  if (has_tube && has_grid) throw InvalidInputError("grid", "give either \"tube\" or \"grid\", not both");
  ControlPolylines input = preset_from_json(preset, {design_keys, !has_tube && !has_grid});
  if (has_grid) {
    forbid_profile(preset, "grid");
    const json& grid = preset["grid"];
    json_only_keys(grid, "grid", {"u_heights", "w_heights"});
    const std::vector<double> u = json_numbers(json_member(grid, "grid", "u_heights"), "grid.u_heights");
    const std::vector<double> w = json_numbers(json_member(grid, "grid", "w_heights"), "grid.w_heights");
    // The base cell (0,0) is the tube [u_0, w_0, u_1, w_1].
    return in_user_terms([&] { return grid_design(std::move(input), u, w); }, [](std::size_t k) {
      return std::string(k % 2 == 0 ? "grid.u_heights[" : "grid.w_heights[") + std::to_string(k / 2) + "]";
    });
  }
  if (has_tube) {
    forbid_profile(preset, "tube");
    const json& tube = preset["tube"];
    json_only_keys(tube, "tube", {"type", "apex_heights"});
    const json& type_value = json_member(tube, "tube", "type");
    if (!type_value.is_string()) throw InvalidInputError("tube.type", "expected a string");
    const TubeType type = tube_type_from_string(type_value.get<std::string>(), "tube.type");
    const std::vector<double> z = json_numbers(json_member(tube, "tube", "apex_heights"), "tube.apex_heights");
    if (z.size() != 4) {
      throw InvalidInputError("tube.apex_heights", "expected 4 heights [z_0, z_1, z_2, z_3], got " + std::to_string(z.size()));
    }
    return in_user_terms([&] { return tube_design(std::move(input), type, {z[0], z[1], z[2], z[3]}); },
                         [](std::size_t k) { return "tube.apex_heights[" + std::to_string(k) + "]"; });
  }
  return single_design(std::move(input));
}

void add_row(Design& design, const json& row) {
  json_only_keys(row, "row", {"parent", "side", "free_heights"});
  const std::size_t parent = row.contains("parent") ? json_index(row["parent"], "row.parent") : 0;
  const std::size_t side = json_index(json_member(row, "row", "side"), "row.side");
  const std::vector<double> heights = json_numbers(json_member(row, "row", "free_heights"), "row.free_heights");
  add_face_coupled_row(design.assembly, parent, side, heights, "row");
}

std::string member_name(const json& c, const std::string& field) {
  if (!c.contains("name")) return field;
  if (!c["name"].is_string()) throw InvalidInputError(field + ".name", "expected a string");
  return c["name"].get<std::string>();
}

void add_coupling(Design& design, const json& c, const std::string& field) {
  const json& type_value = json_member(c, field, "type");
  const std::string type = type_value.is_string() ? type_value.get<std::string>() : "";
  Assembly& a = design.assembly;
  if (type == "face") {
    json_only_keys(c, field, {"type", "parent", "side", "free_height", "name"});
    const std::size_t parent = json_index(json_member(c, field, "parent"), field + ".parent");
    const std::size_t side = json_index(json_member(c, field, "side"), field + ".side");
    std::optional<double> height;
    if (c.contains("free_height")) height = json_number(c["free_height"], field + ".free_height");
    MemberSpec spec = face_coupling(a, parent, side, height, field);
    spec.name = member_name(c, field);
    a.add_member(spec);
  } else if (type == "edge") {
    json_only_keys(c, field, {"type", "parent", "vertex", "free_heights", "name"});
    const std::size_t parent = json_index(json_member(c, field, "parent"), field + ".parent");
    const std::size_t vertex = json_index(json_member(c, field, "vertex"), field + ".vertex");
    const std::vector<double> heights = json_numbers(json_member(c, field, "free_heights"), field + ".free_heights");
    MemberSpec spec = edge_sharing(a, parent, vertex, heights, field);
    spec.name = member_name(c, field);
    check_edge_sharing_rays(a, a.add_member(spec), field);
  } else {
    throw InvalidInputError(field + ".type", "expected \"face\" or \"edge\", got " + type_value.dump());
  }
}

/// Other documents phedra reads or writes, named rather than refused key by key.
void refuse_other_documents(const json& document) {
  if (!document.is_object()) return;
  if (document.contains("developed")) {
    throw InvalidInputError("developed", "this is a developed (flat) pattern, not a preset: `phedra develop FILE` folds "
                                         "it and writes the folded preset (docs/presets.md, Developed patterns)");
  }
  if (document.contains("samples") && document.contains("labels")) {
    throw InvalidInputError("", "this is a motion JSON (written by `phedra sample` or `generate -o X.json`), not a "
                                "preset: give the preset it was made from");
  }
  if (document.contains("asset") && document.contains("meshes")) {
    throw InvalidInputError("", "this is a glTF file, not a preset: `phedra view FILE` shows .glb files");
  }
  if (document.contains("file_spec") && document.contains("vertices_coords")) {
    throw InvalidInputError("", "this is a FOLD file, not a preset");
  }
}

}  // namespace

Design design_from_json(const json& document) {
  refuse_other_documents(document);
  const json& preset = preset_object(document);
  if (!preset.is_object()) {
    throw InvalidInputError("", "a preset must be a JSON object, got " + std::string(preset.type_name()));
  }
  Design design = base_design(preset);
  const bool coupled = preset.contains("row") || preset.contains("couplings");
  if (preset.contains("row")) add_row(design, preset["row"]);
  if (preset.contains("couplings")) {
    const json& list = preset["couplings"];
    if (!list.is_array()) throw InvalidInputError("couplings", "expected an array of couplings");
    for (std::size_t k = 0; k < list.size(); ++k) add_coupling(design, list[k], "couplings[" + std::to_string(k) + "]");
  }
  if (coupled) design.kind = "assembly of " + std::to_string(design.assembly.member_count()) + " tubes";
  if (preset.contains("merge")) {
    if (!preset["merge"].is_boolean()) throw InvalidInputError("merge", "expected true or false");
    design.merge = preset["merge"].get<bool>();
    if (design.merge && design.assembly.member_count() < 2) {
      throw InvalidInputError("merge", "needs face-coupled members to merge (this design has one member)");
    }
    if (design.merge) design.kind = "merged " + design.kind;
  }
  return design;
}

Design load_design(const std::filesystem::path& path) { return design_from_json(parse_json_text(read_text_file(path))); }

}  // namespace phedra
