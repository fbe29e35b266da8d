#pragma once
// The planar linkage L_0 in the profile plane pi_0 (MATH.md section 4, paper
// section 3.1): its motion parameter, the case (a)/(b), and S_0, S_1, V_{0,0} at t
// (NetMotion::complete_first_row continues the recursion to the other apexes).

#include "phedra/axial_net.h"

#include <vector>

namespace phedra {

/// Which apex moves with t: S_0 in case (a), S_1 in case (b).
enum class MotionCase { a, b };

const char* to_string(MotionCase c);

/// S_0, S_1 and V_{0,0} = (x, 0, 0) of the axial net at one t (canonical frame).
struct LinkageStart {
  double s0 = 0.0;
  double s1 = 0.0;
  double x = 0.0;
};

class Linkage {
 public:
  Linkage() = default;
  /// Decides the case from the axial net: the first row where |S_0 - V| and
  /// |S_1 - V| differ (build_axial_net has excluded the scissor case with '-').
  /// `column`: A_{i,0}, column 0 of the axial net.
  Linkage(const Points& column, const CanonicalInput& input);

  MotionCase motion_case() const { return case_; }
  /// The bound |t| <= r of the moving bar: V_{0,0} reaches the axis there.
  double bound() const { return moving_radius_; }

  /// S_0(t), S_1(t), V_{0,0}(t). Returns false when t is past the bound (x^2 < 0);
  /// `margin` gets x^2 / r^2 of the moving bar.
  bool start(double t, LinkageStart& out, double& margin) const;
  /// d/dt of start(t) at `at` (= start(t)): exact, from x^2 + t^2 = r^2 and the
  /// other apex's constant distance to V_{0,0}. Returns false at the bound (x = 0),
  /// where the rate is infinite.
  bool rate(double t, const LinkageStart& at, LinkageStart& out) const;

 private:
  MotionCase case_ = MotionCase::a;
  double moving_radius_ = 0.0;      ///< |V_{0,0} - S_moving|
  double other_radius_ = 0.0;       ///< |V_{0,0} - S_other|
  double other_sign_ = 1.0;         ///< sgn of the other apex's z
};

}  // namespace phedra
