#pragma once
// A general P-hedron from three control polylines: construction (everything
// that does not depend on t) and its isometric deformation evaluate(t).

#include "phedra/canonical_frame.h"
#include "phedra/control_polylines.h"
#include "phedra/flexion_interval.h"
#include "phedra/grid_topology.h"
#include "phedra/linkage.h"
#include "phedra/strip_chain.h"

#include <span>
#include <vector>

namespace phedra {

class PHedron {
 public:
  /// Validates the input (validate()) and constructs the axial net, the parallel
  /// net, the motion and the flexion interval. Throws InvalidInputError (naming
  /// the field and index) for every violated assumption of MATH.md.
  explicit PHedron(ControlPolylines input);

  const ControlPolylines& input() const { return input_; }
  /// (m + 1) rows by (n + 2) columns: boundary S_0, V_{i,0..n-1}, boundary S_n.
  const GridTopology& topology() const { return topology_; }
  std::size_t vertex_count() const { return topology_.vertex_count(); }
  std::size_t profile_vertex_count() const { return n_; }

  /// The motion parameter t is the axis coordinate (user frame) of the moving
  /// apex: S_0 in case (a), S_1 in case (b).
  MotionCase motion_case() const { return linkage_.motion_case(); }
  double t_star() const { return t_star_; }
  /// [t_lambda, t_mu] (user t) with the strip that causes each end.
  const FlexionInterval& flexion_interval() const { return interval_; }
  /// t_lambda + fraction * (t_mu - t_lambda); fraction in [0, 1] (InvalidInputError otherwise).
  double t_at_fraction(double fraction) const;

  /// The constructed net at t* (user frame, topology order), before any motion.
  const Points& reference() const { return reference_; }
  /// Bounding-box diagonal of reference(): the length scale of every check.
  double model_size() const { return model_size_; }

  /// Vertex positions at t in the user frame (topology order); `out` has
  /// vertex_count() entries. The motion keeps the axis, the plane pi_0 and the
  /// axis coordinate of V_{0,0} fixed. Throws OutOfIntervalError outside the
  /// flexion interval.
  void evaluate(double t, std::span<Vec3> out) const;
  Points evaluate(double t) const;

  /// Heights <S_j(t), axis> (user frame) of the apexes S_0..S_n at t.
  std::vector<double> apex_heights(double t) const;

  /// The margin of the motion at t (negative where it is not real), and the strip
  /// that has the smallest one.
  StripMargin margin(double t) const;

  const CanonicalFrame& frame() const { return frame_; }

 private:
  double canonical_t(double t) const { return frame_.height_to_canonical(t); }
  StripMargin canonical_margin(double tc) const;

  ControlPolylines input_;
  CanonicalFrame frame_;
  std::size_t n_ = 0;
  GridTopology topology_;
  Linkage linkage_;
  StripChain chain_;
  std::vector<double> ratios_;             ///< rho_{i,j}, (m+1) x (n-1)
  std::vector<double> transversal_scales_; ///< parallel-net factors, (m+1) x n
  Points reference_;
  double model_size_ = 0.0;
  double t_star_ = 0.0;
  FlexionInterval interval_;
};

}  // namespace phedra
