#pragma once
// One quad mesh of a whole assembly. The mesh of every output and report is
// panel_mesh(design) (design.h): the distinct panels. Coupled members' shared
// vertices are welded; a wall two members share (aligned face coupling) is one
// panel belonging to both, kept once, or, when the preset asks to merge, deleted
// (both copies: MATH.md section 6). Panels are numbered by their index here, so
// "panel 12" is face 12 of every exported file.

#include "phedra/assembly.h"

#include <optional>

namespace phedra {

/// A face of one member: its index in the member's topology (row * face_columns + column).
struct MemberFace {
  std::size_t member = 0;
  std::size_t local = 0;
};

struct AssemblyMesh {
  std::vector<VertexRef> vertices;        ///< each mesh vertex: a representative member vertex
  std::vector<Quad> faces;                ///< indices into vertices
  std::vector<std::size_t> face_member;   ///< the member each face comes from
  std::vector<std::size_t> face_local;    ///< its index in that member's topology (row * face_columns + column)
  /// A wall two members share, kept once: the other member's copy (empty for every other face).
  std::vector<std::optional<MemberFace>> face_shared_with;
  std::size_t deleted_faces = 0;          ///< merged: faces removed (both copies of shared strips)
  std::size_t shared_walls = 0;           ///< walls kept once that two members share

  /// Positions of the mesh's vertices in a configuration of the assembly.
  Points positions(const AssemblyConfiguration& configuration) const;
};

/// Members side by side: vertex k of member m keeps its own mesh vertex, and a
/// shared wall appears once per member (the raw member meshes, for tests).
AssemblyMesh separate_mesh(const Assembly& assembly);

/// What happens to a wall two members share.
enum class SharedWalls {
  keep_one,  ///< one panel belonging to both members (the distinct panels)
  remove,    ///< both copies deleted: face-coupled cells become one larger tube
};

/// Shared vertices welded, unused vertices dropped, shared walls kept once or removed.
AssemblyMesh welded_mesh(const Assembly& assembly, SharedWalls walls);

/// For each mesh vertex, the lowest-numbered vertex at its place throughout the
/// motion (itself when none): members' vertices that coincide at every t (a
/// boundary column whose two apex rows meet), found at t*, both flexion limits
/// and two inner samples within 1e-9 of the model size. Exports write faces
/// through it (welded_faces) so that no edge has zero length.
std::vector<std::size_t> coincident_vertices(const AssemblyMesh& mesh, const Assembly& assembly);

/// For each point, the lowest-numbered point within `tolerance` of it in every
/// one of the point sets `at` (all of one size), chained (itself when none).
std::vector<std::size_t> coincident_points(const std::vector<Points>& at, double tolerance);

/// The faces with each corner replaced by coincident_vertices' choice; a face
/// with two corners welded repeats an index: the triangle it is (distinct_corners).
std::vector<Quad> welded_faces(const AssemblyMesh& mesh, const std::vector<std::size_t>& representative);

/// A face's distinct corners in order (3 for a welded triangle, 4 otherwise).
std::vector<std::size_t> distinct_corners(const Quad& q);

/// welded_mesh(assembly, SharedWalls::remove).
AssemblyMesh merged_mesh(const Assembly& assembly);

}  // namespace phedra
