#pragma once
// Developable / flat-foldable patterns (paper section 4, MATH.md section 7;
// issue 7, item 2). The P-hedron is given in its developed state: every profile
// plane is one plane that contains the axis, so the pattern is 2D, points
// (x, z) with x the signed distance from the axis and z the height along it, and
// V = A (no parallel net). In that state all strips are at a bifurcation at
// once, and a real flex out of it need not exist (t_lambda = t* = t_mu).
//
// The motion is MATH.md section 4 written in the pattern plane: the linkage L_0
// moves the apexes, every trajectory vertex keeps its distances to S_0 and S_1
// inside its own plane pi_i (on its side of the axis), the other vertices follow
// the constant ratios, and strip i turns pi_i about the axis by
//   cos(dphi_i) = (x_i^2 + x_{i-1}^2 + (z_i - z_{i-1})^2 - L_i^2) / (2 x_i x_{i-1})
// (L_i the flat length of the trajectory edge), dphi_i = fold_i * acos(...),
// fold_i = +1 or -1 being the strip's mountain/valley choice. cos(dphi_i) = 1 at
// the flat state; the flex in direction s (t increasing: +1) is real for strip i
// iff cos(dphi_i) <= 1 just beyond t* on that side. To first order that is the
// paper's non-expansion criterion
//   <v(P) - v(Q), P - Q> <= 0   for every transversal pair P = V_{i-1,j}, Q = V_{i,j}
// (>= 0 for a pair on opposite sides of the axis, where the flat distance is the
// largest, not the smallest, the planes can give), v the velocities of the planar
// linkage. Every fold choice folds once the direction does (a strip's margin does
// not depend on its branch): the choices fix the crease assignment.

#include "phedra/control_polylines.h"
#include "phedra/grid_topology.h"
#include "phedra/linkage.h"

#include <optional>
#include <string>
#include <vector>

namespace phedra {

struct DevelopedInput {
  std::string name = "developed";
  std::vector<Vec2> trajectory;       ///< (x, z): signed distance from the axis, height
  std::vector<double> apex_heights;   ///< z of S_0..S_n
  std::vector<Sign> signs;            ///< s_1..s_{n-1}
};

/// The non-expansion figures of one direction of motion.
struct FlexDirection {
  int direction = 1;                 ///< +1: t increasing, -1: decreasing
  bool folds = false;                ///< every strip (and the linkage L_0) moves for real
  std::vector<double> expansion;     ///< per strip i = 1..m (index i - 1): worst <v(P)-v(Q), P-Q> * direction, sign-corrected (<= 0 folds)
  std::vector<bool> strip_folds;     ///< per strip: cos(dphi_i) <= 1 just beyond t* (exact, not only first order)
  std::string reason;                ///< why it does not fold (the first strip or the linkage)
  double reach = 0.0;                ///< folds: the t where this side's motion ends (a limit)
  /// folds: at `reach` every profile plane is back in one plane (every strip at a
  /// bifurcation at once): the pattern is flat-foldable, flat again there.
  bool flat_at_reach = false;
};

class DevelopedPattern {
 public:
  /// Builds the flat profiles (MATH.md section 2 in the plane). InvalidInputError for
  /// a trajectory vertex on the axis, equal consecutive apex heights, a sigma-
  /// vertex sent to infinity, a scissor configuration.
  explicit DevelopedPattern(DevelopedInput input);

  const DevelopedInput& input() const { return input_; }
  std::size_t strips() const { return flat_.size() - 1; }  ///< m
  std::size_t columns() const { return flat_.front().size(); }  ///< n
  /// The flat vertices V_{i,j} (x, z), row-major (rows m + 1, columns n).
  const std::vector<std::vector<Vec2>>& flat() const { return flat_; }
  /// rows m + 1 by columns n, open (no boundary columns: they collapse onto the apexes).
  GridTopology topology() const { return GridTopology(flat_.size(), flat_.front().size(), false); }
  MotionCase motion_case() const { return case_; }
  double t_star() const { return t_star_; }
  double size() const { return size_; }  ///< bounding-box diagonal of the flat pattern

  /// Both directions, t increasing first.
  std::vector<FlexDirection> flex_directions() const;

  /// The 3D positions (x cos phi, x sin phi, z) of every vertex at t with the fold
  /// choices `fold` (size m, entries +1/-1), topology order; nullopt where the
  /// motion is not real.
  std::optional<Points> folded(double t, const std::vector<int>& fold) const;

  /// The folded configuration at t as an ordinary preset (its flexion interval
  /// reaches back to the flat state): what every other command reads.
  ControlPolylines folded_preset(double t, const std::vector<int>& fold) const;

  /// The apex heights S_0..S_n at t (nullopt where L_0 is not real).
  std::optional<std::vector<double>> apex_heights(double t) const;

 private:
  /// In-plane positions (x, z) of every vertex at t (nullopt: not real).
  std::optional<std::vector<std::vector<Vec2>>> in_plane(double t) const;
  std::optional<double> cos_turn(std::size_t strip, const std::vector<std::vector<Vec2>>& p) const;

  DevelopedInput input_;
  std::vector<std::vector<Vec2>> flat_;
  std::vector<std::vector<double>> ratio_;  ///< rho_{i,j}, signed
  std::vector<double> r0_, r1_, edge_;      ///< |V_i0 - S_0|, |V_i0 - S_1|, |V_i0 - V_{i-1,0}| (flat)
  MotionCase case_ = MotionCase::a;
  double t_star_ = 0.0;
  double size_ = 1.0;
};

}  // namespace phedra
