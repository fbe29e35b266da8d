#pragma once
// The axial P-hedron at t* (MATH.md section 2, paper steps 1 and 2), built in
// the canonical frame.

#include "phedra/control_polylines.h"
#include "phedra/vector_types.h"

#include <vector>

namespace phedra {

/// The input in the canonical frame (CanonicalFrame applied to ControlPolylines).
struct CanonicalInput {
  Points trajectory;            ///< V_{i,0}, i = 0..m
  Points directions;            ///< d_i (z = 0)
  std::vector<double> heights;  ///< z_0..z_n (canonical: V_{0,0} at z = 0)
  std::vector<Sign> signs;      ///< s_1..s_{n-1}
  double scale = 1.0;           ///< length scale for tolerances
};

struct AxialNet {
  std::size_t rows = 0;     ///< m + 1 profiles
  std::size_t columns = 0;  ///< n vertices per profile
  /// A[i][j] row-major: vertex(i, j) = vertices[i * columns + j].
  Points vertices;
  /// Step 1: A_{i,0} - A_{i-1,0} = edge_scale[i] (V_{i,0} - V_{i-1,0}); edge_scale[0] unused.
  std::vector<double> edge_scale;
  /// Step 2: A[i][j+1] - S_{j+1} = ratio(i, j) (A[i][j] - S_{j+1}), j = 0..n-2; constant
  /// during the motion (rho_{i,j} of MATH.md section 4).
  std::vector<double> ratios;

  const Vec3& vertex(std::size_t i, std::size_t j) const { return vertices[i * columns + j]; }
  double ratio(std::size_t i, std::size_t j) const { return ratios[i * (columns - 1) + j]; }
};

/// Builds the axial net. Throws InvalidInputError when a trajectory edge is
/// parallel to its profile plane, when an axial trajectory vertex falls on the
/// axis, in the scissor case with a '-' sign (paper, Remark 1), or when sigma-
/// sends a vertex to (near) infinity (naming i and j).
/// Step 1 alone: column 0 of the axial net, A_{i,0}, with its edge scales.
/// Throws InvalidInputError for a degenerate trajectory and for '-' signs with a
/// scissor-like row (paper, Remark 1).
struct AxialColumn {
  Points vertices;                 ///< A_{i,0}, i = 0..m
  std::vector<double> edge_scale;  ///< as AxialNet::edge_scale
};
AxialColumn build_axial_column(const CanonicalInput& input);

/// Step 2 for row i: from row[0] = A_{i,0}, fills row[1..n-1] and ratios[0..n-2]
/// (rho_{i,j}). Throws InvalidInputError when a '-' apex sends a vertex to infinity.
void build_axial_row(const CanonicalInput& input, std::size_t i, Vec3* row, double* ratios);

/// The whole axial net (steps 1 and 2).
AxialNet build_axial_net(const CanonicalInput& input);

}  // namespace phedra
