#pragma once
// The flexion interval [t_lambda, t_mu] around t*: the largest interval on which
// the motion is real (MATH.md section 4). Found by stepping out from t* with
// steps predicted from the margin's slope, then bisecting the bracket to
// machine precision.

#include "phedra/strip_chain.h"

#include <functional>
#include <string>

namespace phedra {

/// One end of the flexion interval and the strip that causes it (0: the linkage
/// L_0, V_{0,0} reaching the axis; i >= 1: profile planes pi_{i-1}, pi_i coincide).
struct FlexionLimit {
  double t = 0.0;
  std::size_t strip = 0;
  /// In words: "linkage L_0 (V_{0,0} reaches the axis)" or "strip i (profile planes i-1 and i coincide)".
  std::string cause() const;
};

struct FlexionInterval {
  FlexionLimit lower;  ///< t_lambda
  FlexionLimit upper;  ///< t_mu
  double width() const { return upper.t - lower.t; }
  bool contains(double t) const { return t >= lower.t && t <= upper.t; }
};

/// Margin of the motion at t (value < 0 where it is not real there): the smallest
/// over the strips, and which strip.
using MarginFunction = std::function<StripMargin(double)>;
/// Margin of one strip at t (cheap: the strips are independent).
using StripMarginFunction = std::function<double(double t, std::size_t strip)>;

/// Searches both ends between t* and the hard bounds [lower_bound, upper_bound]
/// (beyond which the margin is certainly negative). Requires margin(t*) > 0.
/// Each end is the last t where the margin is still >= 0, to machine precision:
/// once a step fails, the failing strip's own margin is bisected (O(1) a step)
/// and the whole margin is checked at its root, until no other strip fails first.
FlexionInterval find_flexion_interval(double t_star, double lower_bound, double upper_bound,
                                      const MarginFunction& margin, const StripMarginFunction& strip_margin);

}  // namespace phedra
