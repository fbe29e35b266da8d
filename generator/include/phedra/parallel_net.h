#pragma once
// The general P-hedron as the parallel net of the axial one (MATH.md section 3,
// which corrects the paper's step 3): same rows 0 and 1, the input trajectory
// as column 0, every edge parallel to the axial edge. Faces keep their shape
// during the motion, so the signed scale factors of the edges are constant and
// the general net at any t follows from the axial net at t by one
// multiply-add per vertex.

#include "phedra/axial_net.h"

namespace phedra {

struct ParallelNet {
  std::size_t rows = 0;
  std::size_t columns = 0;  ///< n (no boundary columns)
  /// G at t*, row-major like AxialNet::vertices (canonical frame).
  Points vertices;
  /// G[i][j] - G[i-1][j] = transversal_scale(i, j) (A[i][j] - A[i-1][j]), i >= 1.
  std::vector<double> transversal_scales;

  double transversal_scale(std::size_t i, std::size_t j) const { return transversal_scales[i * columns + j]; }
};

/// Solves the parallel net face by face from the input trajectory (canonical
/// frame). Throws InvalidInputError for a degenerate axial face.
/// Row i of the parallel net (n vertices) and its transversal scales, from row
/// i - 1 of both nets and row i of the axial net; `trajectory` is V_{i,0}, the
/// edge scale that of AxialNet. Rows 0 and 1 copy the axial rows. Throws
/// InvalidInputError for a degenerate axial face.
void build_parallel_row(std::size_t i, std::size_t n, const Vec3* previous_axial, const Vec3* axial,
                        const Vec3* previous_general, const Vec3& trajectory, double edge_scale, Vec3* general,
                        double* scales);

ParallelNet build_parallel_net(const AxialNet& axial, const Points& trajectory);

}  // namespace phedra
