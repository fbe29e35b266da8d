#include "phedra/plot_axes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace phedra {
namespace {

double round_step(double span, int target) {
  const double raw = span / std::max(target, 1);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * p >= raw) return m * p;
  }
  return 10.0 * p;
}

}  // namespace

std::string tick_label(double value, double step) {
  if (std::abs(value) < 0.5 * step) return "0";  // never "-0.00"
  if (step >= 1e5 || step < 1e-4) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.3g", value);  // 8e+06, 2.5e-05
    return buffer;
  }
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  std::string s = buffer;
  if (std::abs(value) < 0.5 * step) s = "0";  // never "-0.00"
  return s;
}

Ticks round_ticks(double lo, double hi, int target) {
  Ticks t;
  if (!std::isfinite(lo) || !std::isfinite(hi)) lo = 0.0, hi = 1.0;  // never a NaN tick (or a cast of one)
  if (!(hi > lo)) hi = lo + 1.0;
  t.step = round_step(hi - lo, target);
  const long first = static_cast<long>(std::ceil(lo / t.step - 1e-9)), last = static_cast<long>(std::floor(hi / t.step + 1e-9));
  for (long k = first; k <= last; ++k) {
    t.values.push_back(static_cast<double>(k) * t.step);
    t.labels.push_back(tick_label(static_cast<double>(k) * t.step, t.step));
  }
  return t;
}

std::pair<double, double> round_range(double lo, double hi, int target) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) lo = 0.0, hi = 1.0;
  if (!(hi > lo)) lo -= 0.5, hi += 0.5;
  const double step = round_step(hi - lo, target);
  return {std::floor(lo / step + 1e-9) * step, std::ceil(hi / step - 1e-9) * step};
}

}  // namespace phedra
