#pragma once
// How an animation's time maps to the motion parameter t (docs/formats.md,
// "Time and t"). At a flexion limit the exact motion has unbounded speed in t:
// vertices move as the square root of t's distance from the limit (the 10 x 10
// array's far vertices sweep 1.2 model sizes in the first 0.1 % of the
// interval). With time linear in t no keyframe spacing a client keeps can follow
// that, so time is linear in t except within `ease` seconds of an end that is a
// flexion limit, where t's distance from the limit grows as the square of the
// time's distance from it (joined with a continuous speed). There the exact
// motion moves at a bounded speed in time, and keyframes bound the error.
//
// A segment runs from t0 (at time `start`) to t1 (at `end`). With phi the
// fraction of its time, e0 and e1 its eased fractions at the start and end,
// k = 1 / (1 - e0/2 - e1/2) and g the fraction of [t0, t1] reached:
//   g = k phi^2 / (2 e0)                  for phi < e0
//   g = k (phi - e0/2)                    for e0 <= phi <= 1 - e1
//   g = 1 - k (1 - phi)^2 / (2 e1)        for phi > 1 - e1
//   t = t0 + g (t1 - t0).

#include <vector>

namespace phedra {

/// The fraction g of a segment's t-range reached at the fraction phi of its time (eased fractions e0, e1).
double eased_fraction(double phi, double e0, double e1);
/// The inverse: the fraction of time at which the fraction g of the t-range is reached.
double eased_time_fraction(double g, double e0, double e1);

struct TimeSegment {
  double start = 0.0, end = 1.0;     ///< animation seconds
  double t0 = 0.0, t1 = 1.0;         ///< motion parameter at start and end
  double ease0 = 0.0, ease1 = 0.0;   ///< eased seconds after start and before end (sum <= end - start)

  double t_at(double seconds) const;
  /// The time showing t (t between t0 and t1).
  double seconds_at(double t) const;
};

/// The segments of an animation in time order (contiguous), forward only; a
/// ping-pong animation plays them back after the last one (time 2 T - s shows
/// what time s shows, T the forward duration).
struct TimeMap {
  std::vector<TimeSegment> segments;
  bool ping_pong = false;

  double forward_seconds() const { return segments.empty() ? 0.0 : segments.back().end; }
  double t_at(double seconds) const;
};

/// Eased seconds at an end: `ease` seconds where the end is a flexion limit,
/// 0 elsewhere, and never more than half the segment's duration.
double ease_at_end(bool at_limit, double ease, double segment_seconds);

}  // namespace phedra
