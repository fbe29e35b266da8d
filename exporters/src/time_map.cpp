#include "phedra/time_map.h"

#include <algorithm>
#include <cmath>

namespace phedra {

double eased_fraction(double phi, double e0, double e1) {
  phi = std::clamp(phi, 0.0, 1.0);
  const double k = 1.0 / (1.0 - 0.5 * e0 - 0.5 * e1);
  if (phi < e0) return k * phi * phi / (2.0 * e0);
  if (phi > 1.0 - e1) return 1.0 - k * (1.0 - phi) * (1.0 - phi) / (2.0 * e1);
  return k * (phi - 0.5 * e0);
}

double eased_time_fraction(double g, double e0, double e1) {
  g = std::clamp(g, 0.0, 1.0);
  const double k = 1.0 / (1.0 - 0.5 * e0 - 0.5 * e1);
  if (e0 > 0.0 && g < 0.5 * k * e0) return std::sqrt(2.0 * e0 * g / k);
  if (e1 > 0.0 && g > 1.0 - 0.5 * k * e1) return 1.0 - std::sqrt(2.0 * e1 * (1.0 - g) / k);
  return g / k + 0.5 * e0;
}

double TimeSegment::t_at(double seconds) const {
  const double duration = end - start;
  if (duration <= 0.0) return t1;
  const double g = eased_fraction((seconds - start) / duration, ease0 / duration, ease1 / duration);
  return g >= 1.0 ? t1 : t0 + g * (t1 - t0);
}

double TimeSegment::seconds_at(double t) const {
  const double duration = end - start;
  if (duration <= 0.0 || t1 == t0) return start;
  const double phi = eased_time_fraction((t - t0) / (t1 - t0), ease0 / duration, ease1 / duration);
  return start + phi * duration;
}

double TimeMap::t_at(double seconds) const {
  if (segments.empty()) return 0.0;
  const double forward = forward_seconds();
  if (ping_pong && seconds > forward) seconds = 2.0 * forward - seconds;
  seconds = std::clamp(seconds, 0.0, forward);
  for (const TimeSegment& s : segments) {
    if (seconds <= s.end) return s.t_at(seconds);
  }
  return segments.back().t1;
}

double ease_at_end(bool at_limit, double ease, double segment_seconds) {
  return at_limit ? std::clamp(ease, 0.0, 0.5 * segment_seconds) : 0.0;
}

}  // namespace phedra
