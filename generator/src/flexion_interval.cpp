#include "phedra/flexion_interval.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace phedra {

std::string FlexionLimit::cause() const {
  if (strip == 0) return "linkage L_0 (V_{0,0} reaches the axis)";
  return "strip " + std::to_string(strip) + " (profile planes " + std::to_string(strip - 1) + " and " +
         std::to_string(strip) + " coincide)";
}

namespace {

/// Bisects [feasible, infeasible] to adjacent doubles with `test` (true: feasible).
template <class Test>
void bisect(double& feasible, double& infeasible, const Test& test) {
  while (true) {
    const double mid = 0.5 * (feasible + infeasible);
    if (mid == feasible || mid == infeasible) return;
    (test(mid) ? feasible : infeasible) = mid;
  }
}

/// Narrows [feasible, infeasible] (where `strip` fails) to adjacent doubles.
FlexionLimit refine(double feasible, double infeasible, std::size_t strip, const MarginFunction& margin,
                    const StripMarginFunction& strip_margin) {
  while (true) {
    double a = feasible, b = infeasible;
    bisect(a, b, [&](double t) { return strip_margin(t, strip) >= 0.0; });
    const StripMargin m = margin(a);
    if (m.value >= 0.0) return {a, strip};  // the next double fails for `strip`
    if (!((a - feasible) * (infeasible - a) > 0.0)) break;  // no progress: not expected
    infeasible = a;  // another strip fails before `strip` does
    strip = m.strip;
  }
  // Fallback: plain bisection with the whole margin.
  bisect(feasible, infeasible, [&](double t) {
    const StripMargin m = margin(t);
    if (m.value < 0.0) strip = m.strip;
    return m.value >= 0.0;
  });
  return {feasible, strip};
}

/// Steps from t* towards `bound` (direction given by its side). Where the margin
/// falls, the step goes 1.5 times past the predicted zero, so a smooth limit is
/// bracketed in a step or two; steps never exceed 1/64 of the span.
FlexionLimit search_end(double t_star, double bound, const MarginFunction& margin,
                        const StripMarginFunction& strip_margin) {
  const double span = std::abs(bound - t_star);
  const double direction = bound > t_star ? 1.0 : -1.0;
  const double max_step = span / 64.0;
  const double min_step = span * 1e-12;
  double t = t_star;
  double value = margin(t_star).value;
  double step = max_step / 16.0;
  while (true) {
    double next = t + direction * step;
    if ((next - bound) * direction >= 0.0) next = bound;
    const StripMargin m = margin(next);
    if (m.value < 0.0) return refine(t, next, m.strip, margin, strip_margin);
    if (next == bound) return {bound, m.strip};
    const double slope = (m.value - value) / std::abs(next - t);
    if (slope < 0.0) {
      step = std::clamp(1.5 * m.value / -slope, min_step, max_step);
    } else {
      step = std::min(2.0 * step, max_step);
    }
    t = next;
    value = m.value;
  }
}

}  // namespace

FlexionInterval find_flexion_interval(double t_star, double lower_bound, double upper_bound,
                                      const MarginFunction& margin, const StripMarginFunction& strip_margin) {
  FlexionInterval interval;
  interval.lower = search_end(t_star, lower_bound, margin, strip_margin);
  interval.upper = search_end(t_star, upper_bound, margin, strip_margin);
  return interval;
}

}  // namespace phedra
