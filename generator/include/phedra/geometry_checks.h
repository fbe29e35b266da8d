#pragma once
// Planarity and isometry of one configuration (MATH.md section 8). Values are
// absolute lengths; divide by the model size for the relative figures.

#include "phedra/grid_topology.h"
#include "phedra/vector_types.h"

#include <span>
#include <vector>

namespace phedra {

/// The largest value found and where.
struct Deviation {
  double value = 0.0;
  std::size_t index = 0;  ///< face (planarity) or segment (isometry) index
};

/// Distance of each quad's fourth vertex from the plane of the other three, taking
/// the best-conditioned of the four triangles. Largest over `faces`.
Deviation planarity(const std::vector<Quad>& faces, std::span<const Vec3> vertices);

/// Lengths of the segments (edges, then diagonals).
std::vector<double> segment_lengths(const std::vector<Segment>& segments, std::span<const Vec3> vertices);

/// Largest |length(now) - reference length| over the segments.
Deviation length_deviation(const std::vector<Segment>& segments, std::span<const double> reference_lengths,
                           std::span<const Vec3> vertices);

/// Bounding-box diagonal.
double bounding_box_diagonal(std::span<const Vec3> points);

}  // namespace phedra
