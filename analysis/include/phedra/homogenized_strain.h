#pragma once
// The strain of a whole design along its motion, as the metamaterial figures
// read it (docs/design.md, Metamaterial figures):
//
// - Axes, fixed at t* for the whole motion (never re-sorted): `structural`
//   (the default) puts axis 1 along the trajectory (the chord from the
//   centroid of every member's first profile to that of its last, summed over
//   the members), axis 2 across it where the design spreads most (the
//   principal direction of the vertices projected on the plane normal to axis
//   1) and axis 3 = axis 1 x axis 2; `xyz` takes the user's frame.
// - Stretch: the best affine map (least squares over every vertex) from the
//   configuration at t* to the one at t, x(t) ~ F(t) x(t*) + b(t); the stretch
//   along axis d is |F(t) d|, the stretch of a material fibre that lay along d
//   at t* (rotations do not change it). For a periodic array it is the stretch
//   of the lattice vectors; unlike a bounding-box extent it has no corners
//   where another vertex becomes the extreme one.
// - Its rate: d(ln stretch)/dt from the positions' exact derivative
//   (Assembly::evaluate_rate; at a flexion limit, where it is infinite, a
//   fourth-order central difference next to the limit) through the chain rule;
//   Poisson's ratio nu_jk = -rate_k / rate_j.

#include "phedra/design.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string>

namespace phedra {

enum class MetricsAxes { structural, xyz };

std::string to_string(MetricsAxes axes);
/// "structural" or "xyz"; InvalidInputError("--axes", ...) otherwise.
MetricsAxes parse_metrics_axes(const std::string& name);

class HomogenizedStrain {
 public:
  /// Fixes the axes and the reference (the configuration at t*).
  HomogenizedStrain(const Assembly& assembly, MetricsAxes axes);

  const std::array<Vec3, 3>& axes() const { return axes_; }
  /// Whether the design spreads along axis k at t* (a flat design has no
  /// stretch across its plane): undefined figures otherwise.
  bool defined(int k) const { return defined_[k]; }

  struct State {
    std::array<std::optional<double>, 3> stretch;  ///< |F d_k| (1 at t*)
    std::array<std::optional<double>, 3> rate;     ///< d ln(stretch_k) / dt
  };
  /// The stretches at t (one evaluation of the motion).
  std::array<std::optional<double>, 3> stretch(double t) const;
  /// Stretches and their rates at t (t in the flexion interval).
  State at(double t) const;
  /// The same from a configuration and its exact rates (Assembly::evaluate_rate;
  /// none: the stretches only). Const and touches nothing: safe on several threads.
  State state_of(const AssemblyConfiguration& c, const std::vector<Points>* rates) const;
  /// The same from the members' canonical nets and their rates
  /// (Assembly::evaluate_canonical_rate), the positions never written out.
  State state_of(const std::vector<NetState>& states, const std::vector<NetState>* rates) const;
  /// The moment's weights for fewer points: `point_of` gives, for every member
  /// vertex (members in order, each in topology order), the point it is at
  /// throughout the motion (coupled members' shared vertices: one point);
  /// weight q sums the offsets at t* of the vertices at point q.
  Points weights(const std::vector<std::uint32_t>& point_of, std::size_t points) const;
  /// The same state from those points' positions (and rates) and their weights:
  /// the sums over the vertices, each point once.
  State state_of(const Points& x, const Points* rates, const Points& weights) const;
  /// Samples evaluated together (the energy landscape's): four at once.
  static constexpr std::size_t lanes = 4;
  /// state_of(x, rates, weights) of `lanes` samples at once, their points'
  /// positions and rates (null: none) side by side, [point][coordinate][lane],
  /// into out[0..lanes): each the same bits as that sample's state_of.
  void states_of_lanes(const double* x, const double* rates, const Points& weights, State* out) const;
  /// The positions of the last evaluation (at(t) ends with t's).
  const AssemblyConfiguration& configuration() const { return configuration_; }

  /// The affine map's linear part at t (for the tests).
  Mat3 affine(double t) const;

 private:
  /// M(x) = sum (x - mean x)(X - mean X)^T over the vertices, X at t*.
  Mat3 moment(const std::vector<Points>& members) const;
  /// The same from canonical nets (positions, or `rates`: their rates).
  Mat3 canonical_moment(const std::vector<NetState>& states, bool rates) const;
  Mat3 weighted_moment(const Points& x, const Points& weights) const;
  void weighted_moments_lanes(const double* x, const Points& weights, Mat3* out) const;
  State state_from(const Mat3& f, const std::optional<Mat3>& df) const;
  void evaluate(double t) const;

  const Assembly& assembly_;
  std::array<Vec3, 3> axes_;
  std::array<bool, 3> defined_{};
  Points reference_;            ///< X - mean X, every member's vertices in order
  Vec3 anchor_ = Vec3::Zero();  ///< mean X
  Vec3 canonical_anchor_ = Vec3::Zero();  ///< mean X in the canonical frame
  Vec3 reference_sum_ = Vec3::Zero();     ///< sum of reference_ (zero but for rounding)
  Mat3 pseudo_inverse_;         ///< of sum (X - mean)(X - mean)^T
  double h_ = 0.0, lo_ = 0.0, hi_ = 0.0;
  mutable AssemblyConfiguration configuration_;
};

}  // namespace phedra
