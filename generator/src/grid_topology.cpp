#include "phedra/grid_topology.h"

namespace phedra {

GridTopology::GridTopology(std::size_t rows, std::size_t columns, bool cyclic)
    : rows_(rows), columns_(columns), cyclic_(cyclic) {
  const std::size_t face_cols = face_columns();
  faces_.reserve((rows - 1) * face_cols);
  diagonals_.reserve((rows - 1) * face_cols);
  for (std::size_t i = 0; i + 1 < rows; ++i) {
    for (std::size_t c = 0; c < face_cols; ++c) {
      const std::size_t next = (c + 1) % columns;
      faces_.push_back({index(i, c), index(i, next), index(i + 1, next), index(i + 1, c)});
      diagonals_.push_back({index(i, c), index(i + 1, next)});
    }
  }
  for (std::size_t i = 0; i < rows; ++i) {
    for (std::size_t c = 0; c < face_cols; ++c) edges_.push_back({index(i, c), index(i, (c + 1) % columns)});
  }
  for (std::size_t i = 0; i + 1 < rows; ++i) {
    for (std::size_t c = 0; c < columns; ++c) edges_.push_back({index(i, c), index(i + 1, c)});
  }
}

}  // namespace phedra
