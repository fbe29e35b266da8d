#include "phedra/figure_tracker.h"

#include "phedra/geometry_checks.h"

namespace phedra {

FigureTracker::FigureTracker(const GridTopology& topology, std::span<const Vec3> reference, std::string prefix)
    : topology_(topology), prefix_(std::move(prefix)) {
  faces_ = topology.faces();
  segments_ = topology.edges();
  edge_count_ = segments_.size();
  const std::vector<Segment> diagonals = topology.diagonals();
  segments_.insert(segments_.end(), diagonals.begin(), diagonals.end());
  reference_lengths_ = segment_lengths(segments_, reference);
}

std::string FigureTracker::vertex_label(std::size_t vertex) const {
  return "(" + std::to_string(topology_.row_of(vertex)) + "," + std::to_string(topology_.column_of(vertex)) + ")";
}

void FigureTracker::observe(double t, std::span<const Vec3> positions) {
  const Deviation flat = phedra::planarity(faces_, positions);
  if (!(flat.value <= planarity_.value)) {
    planarity_.update(flat.value, t, prefix_ + "face " + vertex_label(faces_[flat.index][0]));
  }
  const Deviation iso = length_deviation(segments_, reference_lengths_, positions);
  if (!(iso.value <= isometry_.value)) {
    const bool diagonal = iso.index >= edge_count_;
    const Segment& s = segments_[iso.index];
    isometry_.update(iso.value, t,
                     prefix_ + (diagonal ? "diagonal " : "edge ") + vertex_label(s[0]) + "-" + vertex_label(s[1]));
  }
}

}  // namespace phedra
