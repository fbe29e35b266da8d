#pragma once
// The motion of the axial trajectory (MATH.md section 4, paper section 3.2):
// V_{i,0}(t) keeps its distances to S_0(t), S_1(t) and V_{i-1,0}(t); of the two
// solutions, mirror images in pi_{i-1}, the branch of the input is kept.

#include "phedra/axial_net.h"

#include <vector>

namespace phedra {

/// How far a strip is from its flexion limit at one t: 1 - c^2 (MATH.md
/// section 4), 0 where the profile planes pi_{i-1} and pi_i coincide.
struct StripMargin {
  double value = 1.0;
  std::size_t strip = 0;  ///< i of the strip between profiles i-1 and i (0: the linkage L_0)
};

inline constexpr double clamp_margin = 1e-9;

class StripChain {
 public:
  StripChain() = default;
  /// Constant distances and branches from the axial net at t*. Throws
  /// InvalidInputError when the input is a bifurcation configuration (a strip
  /// with pi_{i-1} = pi_i).
  /// `column`: A_{i,0}, column 0 of the axial net.
  StripChain(const Points& column, double s0, double s1);

  std::size_t strips() const { return r0_squared_.size(); }

  /// V_{i,0}(t) from V_{i-1,0}(t) = previous and the apexes at t. Returns false
  /// when strip i has no real position at this t; `margin` gets 1 - c^2.
  /// With `clamp`, a margin slightly below zero (down to -clamp_margin: rounding
  /// at a flexion limit) is treated as zero.
  bool advance(std::size_t i, double s0, double s1, const Vec3& previous, Vec3& out, double& margin,
               bool clamp = false) const;

  /// Follows the trajectory from V_{0,0}(t) = first; returns the smallest margin,
  /// or the first strip that fails (value < 0).
  StripMargin trace(double s0, double s1, const Vec3& first) const;

 private:
  // index i - 1 for strip i
  std::vector<double> r0_squared_, r1_squared_, rp_squared_, branch_;
};

}  // namespace phedra
