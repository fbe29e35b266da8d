#include "phedra/assembly_mesh.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace phedra {

Points AssemblyMesh::positions(const AssemblyConfiguration& c) const {
  Points out;
  out.reserve(vertices.size());
  for (const VertexRef& r : vertices) out.push_back(c.members[r.member][r.vertex]);
  return out;
}

AssemblyMesh separate_mesh(const Assembly& assembly) {
  AssemblyMesh mesh;
  for (std::size_t m = 0; m < assembly.member_count(); ++m) {
    const std::size_t offset = mesh.vertices.size();
    const GridTopology& g = assembly.topology(m);
    for (std::size_t v = 0; v < g.vertex_count(); ++v) mesh.vertices.push_back({m, v});
    const std::vector<Quad> faces = g.faces();
    for (std::size_t k = 0; k < faces.size(); ++k) {
      const Quad& q = faces[k];
      mesh.faces.push_back({q[0] + offset, q[1] + offset, q[2] + offset, q[3] + offset});
      mesh.face_member.push_back(m);
      mesh.face_local.push_back(k);
      mesh.face_shared_with.emplace_back();
    }
  }
  return mesh;
}

std::vector<std::size_t> coincident_vertices(const AssemblyMesh& mesh, const Assembly& assembly) {
  const FlexionInterval& f = assembly.flexion_interval();
  std::vector<double> ts{assembly.t_star()};
  if (std::isfinite(f.lower.t) && std::isfinite(f.upper.t)) {
    for (double s : {0.3, 0.7}) ts.push_back(f.lower.t + s * (f.upper.t - f.lower.t));
    ts.push_back(f.lower.t);
    ts.push_back(f.upper.t);
  }
  std::vector<Points> at;
  for (double t : ts) at.push_back(mesh.positions(assembly.evaluate(t)));
  return coincident_points(at, 1e-9 * assembly.model_size());
}

std::vector<std::size_t> coincident_points(const std::vector<Points>& at, double tolerance) {
  const std::size_t n = at.front().size();
  std::vector<std::size_t> representative(n);
  for (std::size_t v = 0; v < n; ++v) representative[v] = v;
  std::vector<std::size_t> by_x(n);
  for (std::size_t v = 0; v < n; ++v) by_x[v] = v;
  const Points& first = at.front();
  std::sort(by_x.begin(), by_x.end(), [&](std::size_t a, std::size_t b) { return first[a].x() < first[b].x(); });
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n && first[by_x[j]].x() - first[by_x[i]].x() <= tolerance; ++j) {
      const std::size_t a = std::min(by_x[i], by_x[j]), b = std::max(by_x[i], by_x[j]);
      const bool together = std::all_of(at.begin(), at.end(), [&](const Points& p) { return (p[a] - p[b]).norm() <= tolerance; });
      if (together) representative[b] = std::min(representative[b], representative[a]);
    }
  }
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t v = 0; v < n; ++v) {
      const std::size_t r = representative[representative[v]];
      changed = changed || r != representative[v];
      representative[v] = r;
    }
  }
  return representative;
}

std::vector<Quad> welded_faces(const AssemblyMesh& mesh, const std::vector<std::size_t>& representative) {
  std::vector<Quad> faces = mesh.faces;
  for (Quad& q : faces) {
    for (std::size_t& v : q) v = representative[v];
  }
  return faces;
}

std::vector<std::size_t> distinct_corners(const Quad& q) {
  std::vector<std::size_t> corners;
  for (std::size_t c : q) {
    if (std::find(corners.begin(), corners.end(), c) == corners.end()) corners.push_back(c);
  }
  return corners;
}

AssemblyMesh merged_mesh(const Assembly& assembly) { return welded_mesh(assembly, SharedWalls::remove); }

AssemblyMesh welded_mesh(const Assembly& assembly, SharedWalls walls) {
  // Weld: every member vertex gets the id of its shared group (or its own).
  std::vector<std::size_t> offset(assembly.member_count() + 1, 0);
  for (std::size_t m = 0; m < assembly.member_count(); ++m) offset[m + 1] = offset[m] + assembly.topology(m).vertex_count();
  std::vector<std::size_t> weld(offset.back());
  for (std::size_t k = 0; k < weld.size(); ++k) weld[k] = k;
  for (const auto& group : assembly.shared_vertices()) {
    const std::size_t id = offset[group.front().member] + group.front().vertex;
    for (const VertexRef& r : group) weld[offset[r.member] + r.vertex] = id;
  }
  // Faces keyed by their welded vertex set; a key seen twice is a shared wall.
  struct Candidate {
    Quad quad;
    std::size_t member;
    std::size_t local;
  };
  std::vector<Candidate> candidates;
  std::map<std::array<std::size_t, 4>, std::vector<std::size_t>> copies;  // key -> candidates
  for (std::size_t m = 0; m < assembly.member_count(); ++m) {
    const std::vector<Quad> faces = assembly.topology(m).faces();
    for (std::size_t k = 0; k < faces.size(); ++k) {
      const Quad& q = faces[k];
      Quad w{weld[offset[m] + q[0]], weld[offset[m] + q[1]], weld[offset[m] + q[2]], weld[offset[m] + q[3]]};
      std::array<std::size_t, 4> key = w;
      std::sort(key.begin(), key.end());
      copies[key].push_back(candidates.size());
      candidates.push_back({w, m, k});
    }
  }
  AssemblyMesh mesh;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const Candidate& c = candidates[k];
    std::array<std::size_t, 4> key = c.quad;
    std::sort(key.begin(), key.end());
    const std::vector<std::size_t>& same = copies[key];
    std::optional<MemberFace> twin;
    if (same.size() > 1) {
      if (walls == SharedWalls::remove) {
        ++mesh.deleted_faces;
        continue;
      }
      if (same.front() != k) continue;  // the other copy of a wall kept once
      twin = MemberFace{candidates[same[1]].member, candidates[same[1]].local};
      ++mesh.shared_walls;
    }
    mesh.faces.push_back(c.quad);  // global (welded) indices for now
    mesh.face_member.push_back(c.member);
    mesh.face_local.push_back(c.local);
    mesh.face_shared_with.push_back(twin);
  }
  // The used vertices in member order (a single member keeps its topology's order).
  std::vector<std::size_t> index(weld.size(), SIZE_MAX);
  for (const Quad& q : mesh.faces) {
    for (std::size_t g : q) index[g] = 0;
  }
  for (std::size_t global = 0; global < index.size(); ++global) {
    if (index[global] == SIZE_MAX) continue;
    const std::size_t m = std::upper_bound(offset.begin(), offset.end(), global) - offset.begin() - 1;
    index[global] = mesh.vertices.size();
    mesh.vertices.push_back({m, global - offset[m]});
  }
  for (Quad& q : mesh.faces) {
    for (std::size_t& g : q) g = index[g];
  }
  return mesh;
}

}  // namespace phedra
