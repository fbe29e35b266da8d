#pragma once
// A symmetric sparse matrix of 3 x 3 node blocks (the stiffness K), assembled in
// place: the pattern from the elements' nodes first (each node's neighbours,
// sorted), then every block added where it belongs. Eigen's setFromTriplets
// took 5-9 % of the modes' time on a 10^4-panel array (9.5e6 triplets,
// 150 MB of them, sorted and summed); this writes each entry once.
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

  /// Adds `block` at rows of node r, columns of node c (both of one element given).
  void add(std::size_t r, std::size_t c, const Mat3& block);

  /// The matrix, 3 nodes square, compressed column-major.
  Eigen::SparseMatrix<double> matrix() const;

 private:
  std::size_t slot(std::size_t r, std::size_t c) const;
  std::vector<std::size_t> start_;      ///< node c's neighbours: rows_[start_[c] .. start_[c + 1])
  std::vector<std::size_t> rows_;       ///< neighbour nodes, ascending in each column
  std::vector<double> values_;          ///< 9 a block, column-major
};

}  // namespace phedra
