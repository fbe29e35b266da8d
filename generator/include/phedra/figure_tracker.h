#pragma once
// Accumulates the worst planarity and isometry of one mesh over many
// configurations, with where (face / segment in grid labels) and at which t.
// Used by the interval checks of a P-hedron and of an assembly.

#include "phedra/grid_topology.h"
#include "phedra/vector_types.h"

#include <span>
#include <string>
#include <vector>

namespace phedra {

/// The worst value of one figure over the configurations seen.
struct WorstCase {
  double value = 0.0;    ///< absolute length
  double t = 0.0;        ///< where it occurs
  std::string location;  ///< which member / face / segment / vertex, in grid labels

  /// Keeps the larger of this and (value, t, location); NaN always wins.
  void update(double v, double at, const std::string& where) {
    if (!(v <= value)) *this = {v, at, where};
  }
};

class FigureTracker {
 public:
  /// `reference` are the positions at t* (lengths are compared with them);
  /// `prefix` starts every location (for example "member 2, ").
  FigureTracker(const GridTopology& topology, std::span<const Vec3> reference, std::string prefix = "");

  void observe(double t, std::span<const Vec3> positions);

  const WorstCase& planarity() const { return planarity_; }
  const WorstCase& isometry() const { return isometry_; }

  /// "(i,c)": a vertex of the grid in its labels.
  std::string vertex_label(std::size_t vertex) const;

 private:
  const GridTopology& topology_;
  std::string prefix_;
  std::vector<Quad> faces_;
  std::size_t edge_count_ = 0;
  std::vector<Segment> segments_;  ///< edges, then one diagonal per face
  std::vector<double> reference_lengths_;
  WorstCase planarity_, isometry_;
};

}  // namespace phedra
