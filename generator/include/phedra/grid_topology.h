#pragma once
// The combinatorics of a P-hedron mesh: a grid of rows (profiles i = 0..m) and
// columns. Open P-hedra have n + 2 columns: c = 0 is the S_0 boundary, c = 1..n
// are V_{i,0..n-1}, c = n + 1 is the S_n boundary (../shared/cases/README.md).
// Closed (tube) grids have cyclic columns.

#include <array>
#include <cstddef>
#include <vector>

namespace phedra {

using Quad = std::array<std::size_t, 4>;
using Segment = std::array<std::size_t, 2>;

class GridTopology {
 public:
  GridTopology() = default;
  /// rows >= 2, columns >= 2 (>= 3 when cyclic).
  GridTopology(std::size_t rows, std::size_t columns, bool cyclic_columns);

  std::size_t rows() const { return rows_; }
  std::size_t columns() const { return columns_; }
  bool cyclic() const { return cyclic_; }
  std::size_t vertex_count() const { return rows_ * columns_; }
  std::size_t index(std::size_t row, std::size_t column) const { return row * columns_ + column; }
  std::size_t row_of(std::size_t vertex) const { return vertex / columns_; }
  std::size_t column_of(std::size_t vertex) const { return vertex % columns_; }

  /// The lists below follow from rows, columns and cyclic alone, so they are not
  /// stored (a 10^6-vertex grid would need 80 bytes a vertex for them): each call
  /// builds its list; face(k), edge(k) and diagonal(k) give single entries.

  /// Quads (i, c), (i, c+1), (i+1, c+1), (i+1, c): face (i, c) is faces()[i * face_columns() + c].
  std::vector<Quad> faces() const;
  std::size_t face_columns() const { return cyclic_ ? columns_ : columns_ - 1; }
  std::size_t face_count() const { return (rows_ - 1) * face_columns(); }
  Quad face(std::size_t k) const {
    const std::size_t i = k / face_columns(), c = k % face_columns(), next = (c + 1) % columns_;
    return {index(i, c), index(i, next), index(i + 1, next), index(i + 1, c)};
  }
  /// Every hinge and boundary edge once: profile edges then transversal edges.
  std::vector<Segment> edges() const;
  std::size_t edge_count() const { return rows_ * face_columns() + (rows_ - 1) * columns_; }
  /// One diagonal per face (corners 0 and 2): with the edges and planarity it
  /// fixes the panel's shape, so it is part of the isometry check.
  std::vector<Segment> diagonals() const;

 private:
  std::size_t rows_ = 0, columns_ = 0;
  bool cyclic_ = false;
};

}  // namespace phedra
