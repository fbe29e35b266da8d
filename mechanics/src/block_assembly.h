#pragma once
// The upper triangle of a symmetric sparse matrix of 3 x 3 node blocks (the
// stiffness K), assembled in place: the pattern from the elements' nodes first
// (each node's neighbours up to itself, sorted), then every block on or above
// the diagonal added where it belongs. Eigen's setFromTriplets took 5-9 % of the
// modes' time on a 10^4-panel array (9.5e6 triplets, 150 MB of them, sorted and
// summed); this writes each entry once, and only the triangle the solvers read
// (half the memory and the additions of the whole matrix; the upper one, which
// CHOLMOD permutes with one transpose where the lower takes two).
#include "phedra/vector_types.h"

#include <Eigen/SparseCore>

#include <cstddef>
#include <span>
#include <vector>

namespace phedra {

class BlockAssembly {
 public:
  /// `nodes` nodes; the elements, each its nodes (every pair of them a block).
  BlockAssembly(std::size_t nodes, const std::vector<std::span<const std::size_t>>& elements);

  /// Adds `block` at rows of node r, columns of node c (both of one element
  /// given, r <= c: the block of r > c is this one's transpose, added with (c, r)).
  void add(std::size_t r, std::size_t c, const Mat3& block);

  /// The upper triangle (diagonal included), 3 nodes square, compressed column-major.
  Eigen::SparseMatrix<double> upper() const;

 private:
  std::size_t slot(std::size_t r, std::size_t c) const;
  std::vector<std::size_t> start_;      ///< node c's neighbours: rows_[start_[c] .. start_[c + 1])
  std::vector<std::size_t> rows_;       ///< neighbours up to c, ascending in each column
  std::vector<double> values_;          ///< 9 a block, column-major
};

}  // namespace phedra
