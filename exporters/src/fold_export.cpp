#include "phedra/fold_export.h"

#include "phedra/assembly_mesh.h"
#include "phedra/errors.h"
#include "phedra/fold_angle.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <algorithm>
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

/// The FOLD faces: each panel's distinct corners (a triangle where two corners are one welded vertex).
Hinges hinges_of(const std::vector<std::vector<std::size_t>>& faces) {
  Hinges h;
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> index;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const std::size_t n = faces[f].size();
    for (std::size_t e = 0; e < n; ++e) {
      const std::size_t a = faces[f][e], b = faces[f][(e + 1) % n];
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

Vec3 face_normal(const std::vector<std::size_t>& q, const Points& v) {
  if (q.size() == 3) return (v[q[1]] - v[q[0]]).cross(v[q[2]] - v[q[0]]).normalized();
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

/// Fold angles of every edge in one configuration (0 on the boundary). Three
/// panels on an edge (a shared wall): the angle of the first two, the sides of
/// the cell the edge belongs to first.
std::vector<double> fold_angles(const Hinges& h, const std::vector<std::vector<std::size_t>>& faces, const Points& v) {
  std::vector<double> angles(h.edges.size(), 0.0);
  for (std::size_t e = 0; e < h.edges.size(); ++e) {
    if (h.faces[e].size() < 2) continue;
    const Vec3 nf = face_normal(faces[h.faces[e][0]], v), ng = face_normal(faces[h.faces[e][1]], v);
    angles[e] = finite(fold_angle_degrees(nf, ng, v[h.edges[e][0]], v[h.edges[e][1]]));
  }
  return angles;
}

/// Angles within this of 0 are flat (F, written as exactly 0); within this of
/// +-180 fully folded, where rounding may give either sign.
constexpr double flat_degrees = 1e-6;

/// A hinge at +-180 (fully folded, either sign by rounding) takes the sign the
/// same hinge has in the configuration next to it towards t* (`towards`).
void keep_signs(std::vector<double>& angles, const std::vector<double>& towards) {
  for (std::size_t e = 0; e < angles.size(); ++e) {
    if (std::abs(angles[e]) >= 180.0 - flat_degrees && towards[e] != 0.0 && (angles[e] > 0) != (towards[e] > 0)) {
      angles[e] = -angles[e];
    }
  }
}

void write_state(const Hinges& h, const std::vector<double>& raw, json& angles, json& assignment) {
  angles = json::array();
  assignment = json::array();
  for (std::size_t e = 0; e < h.edges.size(); ++e) {
    if (h.faces[e].size() < 2) {
      angles.push_back(0.0);
      assignment.push_back("B");
    } else if (std::abs(raw[e]) < flat_degrees) {
      angles.push_back(0.0);  // FOLD 1.2: a flat (F) edge has fold angle 0
      assignment.push_back("F");
    } else {
      angles.push_back(raw[e]);
      assignment.push_back(raw[e] > 0 ? "V" : "M");
    }
  }
}

}  // namespace

namespace {

FoldNumbering numbering_of(const AssemblyMesh& mesh, const Assembly& a) {
  // Vertices that coincide over the whole motion are one FOLD vertex; a panel
  // with two corners at one place is the triangle it is (no zero-length edge).
  const std::vector<std::size_t> representative = coincident_vertices(mesh, a);
  FoldNumbering n;
  n.vertex.assign(mesh.vertices.size(), SIZE_MAX);
  for (const Quad& q : welded_faces(mesh, representative)) {
    std::vector<std::size_t> corners = distinct_corners(q);
    for (std::size_t& c : corners) {
      if (n.vertex[c] == SIZE_MAX) n.vertex[c] = n.kept.size(), n.kept.push_back(c);
      c = n.vertex[c];
    }
    n.faces.push_back(std::move(corners));
  }
  for (std::size_t v = 0; v < n.vertex.size(); ++v) {
    if (n.vertex[v] == SIZE_MAX && n.vertex[representative[v]] != SIZE_MAX) n.vertex[v] = n.vertex[representative[v]];
  }
  return n;
}

}  // namespace

FoldNumbering fold_numbering(const Design& design) { return numbering_of(panel_mesh(design), design.assembly); }

std::string fold_json(const Design& design, const std::vector<double>& ts, const json& buildability) {
  if (ts.empty()) throw InvalidInputError("", "FOLD export needs at least one t");
  const Assembly& a = design.assembly;
  const AssemblyMesh mesh = panel_mesh(design);
  const FoldNumbering numbering = numbering_of(mesh, a);
  const std::vector<std::size_t>& kept = numbering.kept;
  const std::vector<std::vector<std::size_t>>& faces = numbering.faces;
  const Hinges h = hinges_of(faces);
  auto positions = [&](double t) {
    const Points all = mesh.positions(a.evaluate(t));
    Points out;
    out.reserve(kept.size());
    for (std::size_t v : kept) out.push_back(all[v]);
    return out;
  };
  // The key frame is the design configuration t*; the frames are the given t,
  // each hinge's fold angle continuous from t* outwards (signs at +-180 kept).
  const double t_star = a.t_star();
  const Points key = positions(t_star);
  const std::vector<double> key_angles = fold_angles(h, faces, key);
  std::vector<std::size_t> order(ts.size());
  for (std::size_t k = 0; k < ts.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return ts[x] < ts[y]; });
  std::vector<Points> coords(ts.size());
  std::vector<std::vector<double>> angles(ts.size());
  for (std::size_t k : order) {
    coords[k] = positions(ts[k]);
    angles[k] = fold_angles(h, faces, coords[k]);
  }
  // Outwards from t*: above it in increasing t, below it in decreasing t.
  const std::vector<double>* previous = &key_angles;
  for (std::size_t k : order) {
    if (ts[k] < t_star) continue;
    keep_signs(angles[k], *previous);
    previous = &angles[k];
  }
  previous = &key_angles;
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    if (ts[*it] >= t_star) continue;
    keep_signs(angles[*it], *previous);
    previous = &angles[*it];
  }

  json fold;
  fold["file_spec"] = 1.2;
  fold["file_creator"] = "phedra";
  fold["file_author"] = "phedra";
  fold["file_title"] = a.name();
  fold["file_description"] = design.kind + ": frame 0 (the key frame) is the design configuration t* = " +
                             std::to_string(t_star) + "; file_frames fold it over t in [" +
                             std::to_string(*std::min_element(ts.begin(), ts.end())) + ", " +
                             std::to_string(*std::max_element(ts.begin(), ts.end())) + "], each at its frame_phedra:t";
  fold["file_classes"] = json::array({"animation"});
  fold["frame_classes"] = {"foldedForm"};
  fold["frame_attributes"] = {"3D", h.manifold ? "manifold" : "nonManifold"};
  fold["frame_unit"] = "unit";
  fold["frame_phedra:t"] = finite(t_star);
  fold["vertices_coords"] = coordinates(key);
  json face_list = json::array();
  for (const auto& f : faces) face_list.push_back(f);
  fold["faces_vertices"] = face_list;
  json edges = json::array(), edge_faces = json::array();
  for (std::size_t e = 0; e < h.edges.size(); ++e) {
    edges.push_back({h.edges[e][0], h.edges[e][1]});
    edge_faces.push_back(h.faces[e].size() < 2 ? json{h.faces[e][0], nullptr} : json(h.faces[e]));
  }
  fold["edges_vertices"] = edges;
  fold["edges_faces"] = edge_faces;
  write_state(h, key_angles, fold["edges_foldAngle"], fold["edges_assignment"]);
  json frames = json::array();
  for (std::size_t k = 0; k < ts.size(); ++k) {
    json frame;
    frame["frame_parent"] = 0;
    frame["frame_inherit"] = true;
    frame["frame_classes"] = {"foldedForm"};
    frame["frame_phedra:t"] = finite(ts[k]);
    frame["vertices_coords"] = coordinates(coords[k]);
    write_state(h, angles[k], frame["edges_foldAngle"], frame["edges_assignment"]);
    frames.push_back(frame);
  }
  fold["file_frames"] = frames;
  if (!buildability.is_null()) fold["phedra:buildability"] = buildability;
  return fold.dump() + "\n";
}

}  // namespace phedra
