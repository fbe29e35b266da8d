#include "phedra/design.h"

#include "phedra/closed_profile.h"
#include "phedra/coupling.h"
#include "phedra/errors.h"
#include "phedra/preset.h"
#include "phedra/tube.h"
#include "phedra/tube_array.h"

#include <optional>

namespace phedra {
namespace {

using nlohmann::json;

const std::vector<std::string> design_keys{"tube", "grid", "row", "couplings", "merge"};

void check_keys(const json& object, const std::string& field, const std::vector<std::string>& known) {
  if (!object.is_object()) throw InvalidInputError(field, "expected an object, got " + std::string(object.type_name()));
  for (const auto& [key, value] : object.items()) {
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      throw InvalidInputError(field + "." + key, "unknown key (known: " + list + ")");
    }
  }
}

const json& member(const json& object, const std::string& field, const char* key) {
  auto it = object.find(key);
  if (it == object.end()) throw InvalidInputError(field + "." + key, "missing (required key)");
  return *it;
}

std::string profile_kind(const PHedron& p) {
  if (const std::optional<TubeType> type = recognise_tube(p.input())) return std::string(to_string(*type)) + " tube";
  if (p.closed()) return "closed " + std::to_string(closed_profile_sides(p.input())) + "-gon tube";
  return "open P-hedron";
}

void forbid_profile(const json& preset, const char* key) {
  for (const char* profile : {"apex_heights", "signs"}) {
    if (preset.contains(profile)) {
      throw InvalidInputError(profile, std::string("not allowed together with \"") + key + "\", which sets the apexes");
    }
  }
}

Design base_design(const json& preset) {
  const bool has_tube = preset.contains("tube"), has_grid = preset.contains("grid");
  if (has_tube && has_grid) throw InvalidInputError("grid", "give either \"tube\" or \"grid\", not both");
  ControlPolylines input = preset_from_json(preset, {design_keys, !has_tube && !has_grid});
  if (has_grid) {
    forbid_profile(preset, "grid");
    const json& grid = preset["grid"];
    check_keys(grid, "grid", {"u_heights", "w_heights"});
    const std::vector<double> u = json_numbers(member(grid, "grid", "u_heights"), "grid.u_heights");
    const std::vector<double> w = json_numbers(member(grid, "grid", "w_heights"), "grid.w_heights");
    TubeGrid built = make_parallelogram_grid(std::move(input), u, w);
    const std::string kind = std::to_string(u.size() - 1) + " x " + std::to_string(w.size() - 1) +
                             " grid of parallelogram cells";
    return {std::move(built.assembly), false, kind};
  }
  if (has_tube) {
    forbid_profile(preset, "tube");
    const json& tube = preset["tube"];
    check_keys(tube, "tube", {"type", "apex_heights"});
    const json& type_value = member(tube, "tube", "type");
    if (!type_value.is_string()) throw InvalidInputError("tube.type", "expected a string");
    const TubeType type = tube_type_from_string(type_value.get<std::string>(), "tube.type");
    const std::vector<double> z = json_numbers(member(tube, "tube", "apex_heights"), "tube.apex_heights");
    if (z.size() != 4) {
      throw InvalidInputError("tube.apex_heights", "expected 4 heights [z_0, z_1, z_2, z_3], got " + std::to_string(z.size()));
    }
    PHedron p = make_tube(std::move(input), type, {z[0], z[1], z[2], z[3]});
    const std::string kind = profile_kind(p);
    return {Assembly(std::move(p), "tube"), false, kind};
  }
  PHedron p(std::move(input));
  const std::string kind = profile_kind(p);
  const std::string name = p.closed() ? "tube" : "P-hedron";
  return {Assembly(std::move(p), name), false, kind};
}

void add_row(Design& design, const json& row) {
  check_keys(row, "row", {"parent", "side", "free_heights"});
  const std::size_t parent = row.contains("parent") ? json_index(row["parent"], "row.parent") : 0;
  const std::size_t side = json_index(member(row, "row", "side"), "row.side");
  const std::vector<double> heights = json_numbers(member(row, "row", "free_heights"), "row.free_heights");
  add_face_coupled_row(design.assembly, parent, side, heights, "row");
}

std::string member_name(const json& c, const std::string& field) {
  if (!c.contains("name")) return field;
  if (!c["name"].is_string()) throw InvalidInputError(field + ".name", "expected a string");
  return c["name"].get<std::string>();
}

void add_coupling(Design& design, const json& c, const std::string& field) {
  const json& type_value = member(c, field, "type");
  const std::string type = type_value.is_string() ? type_value.get<std::string>() : "";
  Assembly& a = design.assembly;
  if (type == "face") {
    check_keys(c, field, {"type", "parent", "side", "free_height", "name"});
    const std::size_t parent = json_index(member(c, field, "parent"), field + ".parent");
    const std::size_t side = json_index(member(c, field, "side"), field + ".side");
    std::optional<double> height;
    if (c.contains("free_height")) height = json_number(c["free_height"], field + ".free_height");
    MemberSpec spec = face_coupling(a, parent, side, height, field);
    spec.name = member_name(c, field);
    a.add_member(spec);
  } else if (type == "edge") {
    check_keys(c, field, {"type", "parent", "vertex", "free_heights", "name"});
    const std::size_t parent = json_index(member(c, field, "parent"), field + ".parent");
    const std::size_t vertex = json_index(member(c, field, "vertex"), field + ".vertex");
    const std::vector<double> heights = json_numbers(member(c, field, "free_heights"), field + ".free_heights");
    MemberSpec spec = edge_sharing(a, parent, vertex, heights, field);
    spec.name = member_name(c, field);
    check_edge_sharing_rays(a, a.add_member(spec), field);
  } else {
    throw InvalidInputError(field + ".type", "expected \"face\" or \"edge\", got " + type_value.dump());
  }
}

}  // namespace

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

#include "phedra/assembly_mesh.h"

#include <memory>

namespace phedra {

AssemblyMesh panel_mesh(const Design& design) {
  return welded_mesh(design.assembly, design.merge ? SharedWalls::remove : SharedWalls::keep_one);
}

MotionDocument motion_document(const Design& design) {
  const Assembly& a = design.assembly;
  if (a.member_count() == 1) {
    MotionDocument d = motion_document(a.base());
    d.kind = design.kind;
    return d;
  }
  MotionDocument d;
  d.name = a.name();
  d.kind = design.kind;
  d.t_star = a.t_star();
  d.motion_case = to_string(a.base().motion_case());
  d.t_lambda = a.flexion_interval().lower.t;
  d.t_mu = a.flexion_interval().upper.t;
  for (std::size_t m = 0; m < a.member_count(); ++m) d.members.push_back(a.member_name(m));
  auto mesh = std::make_shared<AssemblyMesh>(panel_mesh(design));
  for (const VertexRef& r : mesh->vertices) {
    const GridTopology& g = a.topology(r.member);
    d.labels.push_back({r.member, g.row_of(r.vertex), g.column_of(r.vertex)});
  }
  d.faces = mesh->faces;
  d.face_members = mesh->face_member;
  d.positions = [&a, mesh](double t, Points& out) { out = mesh->positions(a.evaluate(t)); };
  return d;
}

}  // namespace phedra
