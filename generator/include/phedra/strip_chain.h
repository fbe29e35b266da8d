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
  /// `flipped`: strip i takes the mirror of its input branch (the continuation of
  /// the motion through a flexion limit of strip i, paper Remark 3).
  bool advance(std::size_t i, double s0, double s1, const Vec3& previous, Vec3& out, double& margin,
               bool clamp = false, bool flipped = false) const;

  /// d/dt of V_{i,0} = `at` (advance's result) from the rates of the apexes and of
  /// V_{i-1,0} = previous: exact, the 3 x 3 system of its constant distances to
  /// S_0, S_1 and V_{i-1,0} differentiated. Returns false where it is singular
  /// (det(X-S_0, X-S_1, X-P) = 0: the strip's flexion limit, the rate infinite).
  bool rate(double s0, double s1, const Vec3& previous, const Vec3& at, double ds0, double ds1,
            const Vec3& previous_rate, Vec3& out) const;

  /// The smallest margin over the strips at apexes s0, s1 with V_{0,0}(t) =
  /// (x, 0, 0), and its strip. Each strip's margin depends only on the heights and
  /// radii of its two circles (V_{i,0} has the height h_i and the distance r_i
  /// from the axis whatever its angle), so no vertex is computed and the strips
  /// are independent. Negative (continuous in t) where the motion is not real: a
  /// strip with 1 - c^2 < 0, or with no circle at all (r_i^2 <= 0).
  StripMargin margin(double s0, double s1, double x) const;
  /// The margin of strip i >= 1 alone, in O(1): the same arithmetic as margin().
  double strip_margin(std::size_t i, double s0, double s1, double x) const;

 private:
  // index i - 1 for strip i
  std::vector<double> r0_squared_, r1_squared_, rp_squared_, branch_;
  std::vector<double> half_difference_;  ///< (r1^2 - r0^2) / 2

  /// Height and squared radius of the circle of V_{k+1,0} (index k = i - 1).
  void circle(std::size_t k, double s0, double middle, double inverse, double& h, double& r2) const {
    h = middle + half_difference_[k] * inverse;
    r2 = r0_squared_[k] - (h - s0) * (h - s0);
  }
  /// 1 - c^2 of strip k + 1 from its circle and the previous one's.
  double strip_value(std::size_t k, double h, double r2, double previous_h, double previous_r2) const;
};

}  // namespace phedra
