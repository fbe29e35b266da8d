#include "phedra/fold_export.h"

#include "phedra/assembly_mesh.h"
#include "phedra/errors.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <map>

namespace phedra {
namespace {

using nlohmann::json;

struct Hinges {
  std::vector<std::array<std::size_t, 2>> edges;           ///< vertex pairs, as traversed by the first face
  /// The faces on each edge, in the order met: one on the boundary, two on a
  /// hinge, three where a wall two cells share meets their sides.
  std::vector<std::vector<std::size_t>> faces;
  bool manifold = true;
};

Hinges hinges_of(const std::vector<Quad>& faces) {
  Hinges h;
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> index;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (int e = 0; e < 4; ++e) {
      const std::size_t a = faces[f][e], b = faces[f][(e + 1) % 4];
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto it = index.find(key);
      if (it == index.end()) {
        index[key] = h.edges.size();
        h.edges.push_back({a, b});
        h.faces.push_back({f});
      } else {
        h.faces[it->second].push_back(f);
        h.manifold = h.manifold && h.faces[it->second].size() <= 2;
      }
    }
  }
  return h;
}

Vec3 face_normal(const Quad& q, const Points& v) {
  // Newell's normal of the quad: robust for planar quads in any order.
  return (v[q[2]] - v[q[0]]).cross(v[q[3]] - v[q[1]]).normalized();
}

double finite(double x) {
  if (!std::isfinite(x)) throw Error(ExitCode::internal, "refusing to write a non-finite number to FOLD");
  return x;
}

json coordinates(const Points& v) {
  json out = json::array();
  for (const Vec3& p : v) out.push_back({finite(p.x()), finite(p.y()), finite(p.z())});
  return out;
}

void fold_state(const Hinges& h, const std::vector<Quad>& faces, const Points& v, json& angles, json& assignment) {
  angles = json::array();
  assignment = json::array();
  for (std::size_t e = 0; e < h.edges.size(); ++e) {
    if (h.faces[e].size() < 2) {
      angles.push_back(0.0);
      assignment.push_back("B");
      continue;
    }
    // Three panels on an edge (a shared wall): the angle of the first two, the
    // sides of the cell the edge belongs to first.
    const Vec3 nf = face_normal(faces[h.faces[e][0]], v), ng = face_normal(faces[h.faces[e][1]], v);
    const double angle = finite(fold_angle_degrees(nf, ng, v[h.edges[e][0]], v[h.edges[e][1]]));
    angles.push_back(angle);
    assignment.push_back(std::abs(angle) < 1e-6 ? "F" : (angle > 0 ? "V" : "M"));
  }
}

}  // namespace

double fold_angle_degrees(const Vec3& nf, const Vec3& ng, const Vec3& a, const Vec3& b) {
  const Vec3 edge = (b - a).normalized();
  return std::atan2(-nf.cross(ng).dot(edge), nf.dot(ng)) * 180.0 / M_PI;
}

std::string fold_json(const Design& design, const std::vector<double>& ts, const json& buildability) {
  if (ts.empty()) throw InvalidInputError("", "FOLD export needs at least one t");
  const Assembly& a = design.assembly;
  const AssemblyMesh mesh = panel_mesh(design);
  const Hinges h = hinges_of(mesh.faces);
  json fold;
  fold["file_spec"] = 1.2;
  fold["file_creator"] = "phedra";
  fold["file_author"] = "phedra";
  fold["file_title"] = a.name();
  fold["file_description"] = design.kind + ", folding over t in [" + std::to_string(ts.front()) + ", " +
                             std::to_string(ts.back()) + "]; frame k is the configuration at frame_phedra:t";
  fold["file_classes"] = ts.size() > 1 ? json::array({"animation"}) : json::array({"singleModel"});
  fold["frame_classes"] = {"foldedForm"};
  fold["frame_attributes"] = {"3D", h.manifold ? "manifold" : "nonManifold"};
  fold["frame_unit"] = "unit";
  fold["frame_phedra:t"] = finite(ts.front());
  Points v = mesh.positions(a.evaluate(ts.front()));
  fold["vertices_coords"] = coordinates(v);
  json faces = json::array();
  for (const Quad& q : mesh.faces) faces.push_back({q[0], q[1], q[2], q[3]});
  fold["faces_vertices"] = faces;
  json edges = json::array(), edge_faces = json::array();
  for (std::size_t e = 0; e < h.edges.size(); ++e) {
    edges.push_back({h.edges[e][0], h.edges[e][1]});
    edge_faces.push_back(h.faces[e].size() < 2 ? json{h.faces[e][0], nullptr} : json(h.faces[e]));
  }
  fold["edges_vertices"] = edges;
  fold["edges_faces"] = edge_faces;
  fold_state(h, mesh.faces, v, fold["edges_foldAngle"], fold["edges_assignment"]);
  json frames = json::array();
  for (std::size_t k = 1; k < ts.size(); ++k) {
    v = mesh.positions(a.evaluate(ts[k]));
    json frame;
    frame["frame_parent"] = 0;
    frame["frame_inherit"] = true;
    frame["frame_classes"] = {"foldedForm"};
    frame["frame_phedra:t"] = finite(ts[k]);
    frame["vertices_coords"] = coordinates(v);
    fold_state(h, mesh.faces, v, frame["edges_foldAngle"], frame["edges_assignment"]);
    frames.push_back(frame);
  }
  if (!frames.empty()) fold["file_frames"] = frames;
  if (!buildability.is_null()) fold["phedra:buildability"] = buildability;
  return fold.dump() + "\n";
}

}  // namespace phedra
