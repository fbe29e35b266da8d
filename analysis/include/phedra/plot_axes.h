#pragma once
// Axes people can read: ticks at round values (1, 2 or 5 times a power of
// ten), their labels without rounding noise, ranges that end on a tick.

#include <string>
#include <vector>

namespace phedra {

struct Ticks {
  double step = 1.0;
  std::vector<double> values;  ///< multiples of step within [lo, hi], increasing
  std::vector<std::string> labels;
};

/// About `target` ticks over [lo, hi] (lo < hi), at multiples of a 1-2-5 step.
Ticks round_ticks(double lo, double hi, int target = 5);

/// [lo, hi] widened to multiples of the 1-2-5 step round_ticks would choose.
std::pair<double, double> round_range(double lo, double hi, int target = 5);

/// A tick value as text with as many decimals as its step needs ("0.25", "1.5", "-10").
std::string tick_label(double value, double step);

}  // namespace phedra
