#pragma once
// Where a collision starts, between a sample free of it and the next that has
// it: the sweeps of the zero-thickness panels and of the thick plates.

#include <cmath>
#include <optional>

namespace phedra {

/// Halves [good, bad] (good free, bad with `hit`) until it is within
/// `resolution` (80 halvings at most): test(mid) returns the hit at mid, or
/// nothing when mid is free (and then keeps what it tracks from there on).
/// `good` ends at the last free t; returns the hit nearest to it.
template <class Hit, class Test>
Hit bisect_first_hit(double& good, double bad, double resolution, Hit hit, Test&& test) {
  for (int halving = 0; halving < 80 && std::abs(bad - good) > resolution; ++halving) {
    const double mid = 0.5 * (good + bad);
    if (std::optional<Hit> here = test(mid)) {
      bad = mid;
      hit = *here;
    } else {
      good = mid;
    }
  }
  return hit;
}

}  // namespace phedra
