#include "phedra/flexion_interval.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace phedra {
namespace {

/// Bisects [feasible, infeasible] down to adjacent doubles.
FlexionLimit bisect(double feasible, double infeasible, std::size_t strip, const MarginFunction& margin) {
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double mid = 0.5 * (feasible + infeasible);
    if (mid == feasible || mid == infeasible) break;
    const StripMargin m = margin(mid);
    if (m.value >= 0.0) {
      feasible = mid;
    } else {
      infeasible = mid;
      strip = m.strip;
    }
  }
  return {feasible, strip};
}

/// Steps from t* towards `bound` (direction given by its side).
FlexionLimit search_end(double t_star, double bound, const MarginFunction& margin) {
  const double span = std::abs(bound - t_star);
  const double direction = bound > t_star ? 1.0 : -1.0;
  const double max_step = span / 128.0;
  const double min_step = span * 1e-9;
  double t = t_star;
  double value = margin(t_star).value;
  double step = max_step / 16.0;
  while (true) {
    double next = t + direction * step;
    if ((next - bound) * direction >= 0.0) next = bound;
    const StripMargin m = margin(next);
    if (m.value < 0.0) return bisect(t, next, m.strip, margin);
    if (next == bound) return {bound, m.strip};
    const double slope = (m.value - value) / step;
    if (slope < 0.0) {
      step = std::clamp(0.5 * m.value / -slope, min_step, max_step);
    } else {
      step = std::min(2.0 * step, max_step);
    }
    t = next;
    value = m.value;
  }
}

}  // namespace

FlexionInterval find_flexion_interval(double t_star, double lower_bound, double upper_bound,
                                      const MarginFunction& margin) {
  FlexionInterval interval;
  interval.lower = search_end(t_star, lower_bound, margin);
  interval.upper = search_end(t_star, upper_bound, margin);
  return interval;
}

}  // namespace phedra
