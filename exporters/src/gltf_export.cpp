#include "phedra/gltf_export.h"

#include "gltf_parts.h"

#include "phedra/assembly_check.h"
#include "phedra/errors.h"

#include <tiny_gltf.h>

#include <cmath>
#include <sstream>

namespace phedra {
namespace {

using namespace gltf;

std::array<double, 3> hsv_to_rgb(double h, double s, double v) {
  const double c = v * s, x = c * (1 - std::abs(std::fmod(h * 6, 2.0) - 1)), m = v - c;
  const int sector = static_cast<int>(h * 6) % 6;
  const double table[6][3] = {{c, x, 0}, {x, c, 0}, {0, c, x}, {0, x, c}, {x, 0, c}, {c, 0, x}};
  return {table[sector][0] + m, table[sector][1] + m, table[sector][2] + m};
}

/// extras.phedra.time_map: how time maps to t (time_map.h, docs/formats.md).
tinygltf::Value time_map_value(const TimeMap& time, double ease_seconds) {
  auto pair = [](double a, double b) { return tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(a), tinygltf::Value(b)}); };
  tinygltf::Value::Array segments;
  for (const TimeSegment& s : time.segments) {
    tinygltf::Value::Object o;
    o["seconds"] = pair(s.start, s.end);
    o["t"] = pair(s.t0, s.t1);
    o["ease_seconds"] = pair(s.ease0, s.ease1);
    segments.push_back(tinygltf::Value(o));
  }
  tinygltf::Value::Object out;
  out["ease_seconds"] = tinygltf::Value(ease_seconds);
  out["segments"] = tinygltf::Value(segments);
  out["ping_pong"] = tinygltf::Value(time.ping_pong);
  return tinygltf::Value(out);
}

}  // namespace

std::string gltf_bytes(const Design& design, const GltfOptions& options, GltfReport* report) {
  const Assembly& assembly = design.assembly;
  AssemblyMesh mesh = panel_mesh(design);
  mesh.faces = welded_faces(mesh, coincident_vertices(mesh, assembly));
  const MotionPath path = options.cycle ? cycle_path(design, mesh, options) : interval_path(design, mesh, options);
  const double size = assembly.model_size();
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "phedra";
  BufferBuilder buffer(model);
  // Materials: one per member, double-sided.
  for (std::size_t m = 0; m < assembly.member_count(); ++m) {
    const auto rgb = hsv_to_rgb(std::fmod(0.58 + 0.618034 * static_cast<double>(m), 1.0), 0.55, 0.9);
    tinygltf::Material material;
    material.name = assembly.member_name(m);
    material.doubleSided = true;
    material.pbrMetallicRoughness.baseColorFactor = {rgb[0], rgb[1], rgb[2], 1.0};
    material.pbrMetallicRoughness.metallicFactor = 0.0;
    material.pbrMetallicRoughness.roughnessFactor = 0.8;
    model.materials.push_back(material);
  }

  GltfReport figures;
  figures.tolerance = options.keyframes.relative_tolerance * size;
  figures.model_size = size;
  tinygltf::Value::Array keyframe_t;
  if (options.morph) {
    build_morph(model, buffer, design, mesh, path, options, figures, keyframe_t);
  } else {
    build_nodes(model, buffer, design, mesh, path, options, figures, keyframe_t);
  }

  if (!options.static_t) figures.vertex_error_t = path.t_of(figures.vertex_error_t);
  tinygltf::Value::Object phedra;
  phedra["name"] = tinygltf::Value(assembly.name());
  phedra["kind"] = tinygltf::Value(design.kind);
  phedra["t_lambda"] = tinygltf::Value(assembly.flexion_interval().lower.t);
  phedra["t_mu"] = tinygltf::Value(assembly.flexion_interval().upper.t);
  if (options.range && !options.static_t) {
    phedra["animated_interval"] =
        tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(options.range->first), tinygltf::Value(options.range->second)});
  }
  phedra["t_star"] = tinygltf::Value(assembly.t_star());
  phedra["model_size"] = tinygltf::Value(size);
  phedra["up"] = tinygltf::Value(std::string("glTF (x, y, z) = preset (x, z, -y)"));
  if (options.static_t) {
    phedra["t"] = tinygltf::Value(*options.static_t);
  } else {
    phedra["seconds"] = tinygltf::Value(options.seconds);
    if (options.cycle) {
      tinygltf::Value::Array passes;
      for (const PHedron::Pass& pass : assembly.base().configuration_cycle().passes) {
        tinygltf::Value::Object p;
        p["from"] = tinygltf::Value(pass.from);
        p["to"] = tinygltf::Value(pass.to);
        p["switched_strip"] = tinygltf::Value(static_cast<int>(pass.switched));
        passes.push_back(tinygltf::Value(p));
      }
      phedra["cycle"] = tinygltf::Value(passes);
    }
    phedra["ping_pong"] = tinygltf::Value(options.ping_pong);
    phedra["keyframe_t"] = tinygltf::Value(keyframe_t);
    phedra["time_map"] = time_map_value(path.time, options.ease * options.seconds);
    // Measured at 15 points of every keyframe interval (absolute, model units).
    phedra["max_vertex_error"] = tinygltf::Value(figures.max_vertex_error);
    phedra["max_vertex_error_t"] = tinygltf::Value(figures.vertex_error_t);
    phedra["vertex_tolerance"] = tinygltf::Value(figures.tolerance);
    // Next to a flexion limit: keyframe intervals at the minimum spacing still above the tolerance.
    phedra["limit_vertex_error"] = tinygltf::Value(figures.narrow_vertex_error);
    phedra["limit_seconds"] = tinygltf::Value(figures.narrow_seconds);
    phedra["minimum_keyframe_spacing_seconds"] =
        tinygltf::Value(options.keyframes.minimum_spacing * path.seconds_of(path.hi));
    if (!options.morph) {
      phedra["max_hinge_opening"] = tinygltf::Value(figures.max_opening);
      phedra["hinge_tolerance"] = tinygltf::Value(figures.tolerance);
    }
  }
  phedra["representation"] = tinygltf::Value(std::string(options.morph ? "morph targets" : "nodes"));
  phedra["panels"] = tinygltf::Value(static_cast<int>(figures.panels));
  if (!options.morph) phedra["tree_depth"] = tinygltf::Value(static_cast<int>(figures.tree_depth));
  // The check figures over the interval, relative to the model size, for viewers.
  const AssemblyCheckReport check = check_assembly(assembly, {});
  tinygltf::Value::Object check_figures;
  check_figures["passed"] = tinygltf::Value(check.passed());
  check_figures["planarity"] = tinygltf::Value(check.planarity.value / size);
  check_figures["isometry"] = tinygltf::Value(check.isometry.value / size);
  check_figures["closure"] = tinygltf::Value(check.closure.value / size);
  check_figures["shared_vertices"] = tinygltf::Value(check.shared.value / size);
  check_figures["samples"] = tinygltf::Value(static_cast<int>(check.samples));
  phedra["check"] = tinygltf::Value(check_figures);
  if (!options.buildability.is_null()) phedra["buildability"] = to_value(options.buildability);
  if (!options.preset_text.empty()) phedra["preset"] = tinygltf::Value(options.preset_text);
  tinygltf::Value::Object extras;
  extras["phedra"] = tinygltf::Value(phedra);
  // Where clients read it: three.js keeps asset.extras in parser.json; Blender's
  // importer drops it but keeps scenes[0].extras as the scene's custom properties.
  model.asset.extras = tinygltf::Value(extras);
  model.scenes[0].extras = tinygltf::Value(extras);

  tinygltf::TinyGLTF writer;
  std::ostringstream out;
  if (!writer.WriteGltfSceneToStream(&model, out, !options.binary, options.binary)) {
    throw Error(ExitCode::internal, "glTF serialisation failed");
  }
  std::string bytes = out.str();
  if (report) {
    *report = figures;
    report->bytes = bytes.size();
  }
  return bytes;
}

}  // namespace phedra
