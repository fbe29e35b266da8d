#pragma once
// A panel in the two nets MATH.md section 9 reads its shape from: its corners
// in the axial net A and in the general (parallel) net G of its member at t*,
// canonical frame. Every edge of G is a constant signed multiple of the same
// edge of A, so G's corner turns are A's times the signs of the two edge scales
// at the corner.

#include "phedra/assembly.h"
#include "phedra/assembly_mesh.h"
#include "phedra/panel_shape.h"

#include <array>
#include <vector>

namespace phedra {

struct PanelNets {
  PanelCorners axial;    ///< A, in the face's corner order (mesh order)
  PanelCorners general;  ///< G, same order
  /// A face of a boundary column of an open P-hedron (towards S_0 or S_n): its
  /// axial face is the triangle with the apex, its general face a trapezoid.
  bool boundary = false;
  std::size_t row = 0;     ///< i: the face lies between profiles i and i + 1
  /// j: the face lies between net columns j and j + 1 (vertices V_{i,j}, V_{i,j+1});
  /// for a boundary face, the net column of its transversal edge (0 or n - 1).
  std::size_t column = 0;
  std::size_t net_columns = 0;  ///< n, net columns of the member (a tube's last equals its first)
};

/// Face `local` (row * face_columns + column) of member m.
PanelNets panel_nets(const Assembly& assembly, std::size_t member, std::size_t local);

/// The shape of every panel of `mesh` (a mesh of `assembly`), at t*: the motion keeps it.
std::vector<PanelShape> panel_shapes(const Assembly& assembly, const AssemblyMesh& mesh);

/// Signed scale of an edge of G against the same edge of A: <g, a> / |a|^2.
inline double edge_scale(const Vec3& general, const Vec3& axial) {
  const double a2 = axial.squaredNorm();
  return a2 > 0.0 ? general.dot(axial) / a2 : 0.0;
}

}  // namespace phedra
