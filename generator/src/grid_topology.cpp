#include "phedra/grid_topology.h"

namespace phedra {

GridTopology::GridTopology(std::size_t rows, std::size_t columns, bool cyclic)
    : rows_(rows), columns_(columns), cyclic_(cyclic) {}

std::vector<Quad> GridTopology::faces() const {
  std::vector<Quad> faces(face_count());
  for (std::size_t k = 0; k < faces.size(); ++k) faces[k] = face(k);
  return faces;
}

std::vector<Segment> GridTopology::diagonals() const {
  std::vector<Segment> diagonals(face_count());
  for (std::size_t k = 0; k < diagonals.size(); ++k) {
    const Quad f = face(k);
    diagonals[k] = {f[0], f[2]};
  }
  return diagonals;
}

std::vector<Segment> GridTopology::edges() const {
  std::vector<Segment> edges;
  edges.reserve(edge_count());
  const std::size_t face_cols = face_columns();
  for (std::size_t i = 0; i < rows_; ++i) {
    for (std::size_t c = 0; c < face_cols; ++c) edges.push_back({index(i, c), index(i, (c + 1) % columns_)});
  }
  for (std::size_t i = 0; i + 1 < rows_; ++i) {
    for (std::size_t c = 0; c < columns_; ++c) edges.push_back({index(i, c), index(i + 1, c)});
  }
  return edges;
}

}  // namespace phedra
