#pragma once
// One quad mesh of a whole assembly: its members side by side (every member
// keeps its vertices), or merged (shared vertices welded and the face strips
// that two members share deleted, both copies: MATH.md section 6).

#include "phedra/assembly.h"

namespace phedra {

struct AssemblyMesh {
  std::vector<VertexRef> vertices;        ///< each mesh vertex: a representative member vertex
  std::vector<Quad> faces;                ///< indices into vertices
  std::vector<std::size_t> face_member;   ///< the member each face comes from
  std::vector<std::size_t> face_local;    ///< its index in that member's topology (row * face_columns + column)
  std::size_t deleted_faces = 0;          ///< merged: faces removed (both copies of shared strips)

  /// Positions of the mesh's vertices in a configuration of the assembly.
  Points positions(const AssemblyConfiguration& configuration) const;
};

/// Members side by side: vertex k of member m keeps its own mesh vertex.
AssemblyMesh separate_mesh(const Assembly& assembly);

/// Shared vertices welded, shared face strips removed (both copies), unused
/// vertices dropped.
AssemblyMesh merged_mesh(const Assembly& assembly);

}  // namespace phedra
