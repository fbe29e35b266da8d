#include "phedra/assembly_mesh.h"

#include <algorithm>
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
