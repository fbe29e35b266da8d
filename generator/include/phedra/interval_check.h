#pragma once
// Planarity, isometry and (for tubes) closure over the whole flexion interval
// (dense samples, both ends and t*), with the worst value and where it occurs.
// Shared by `phedra check`, `phedra info` and the tests; their JSON and text
// forms are io/check_report.h.

#include "phedra/figure_tracker.h"
#include "phedra/phedron.h"
#include "phedra/tolerances.h"

#include <string>
#include <vector>

namespace phedra {

struct CheckOptions {
  /// Uniform samples of [t_lambda, t_mu], ends included (>= 2); t* is added.
  std::size_t samples = 200;
  /// Pass when every figure is at most this times the model size.
  double relative_tolerance = tolerance::check_relative;
  /// Planarity and isometry of every panel too; false: the closure check alone
  /// (closure gaps, shared vertices, reproduction at t*), about three times faster.
  /// Honoured by check_assembly; check_over_interval always measures the shape.
  bool shape = true;
};

struct IntervalCheckReport {
  double model_size = 0.0;
  double tolerance = 0.0;  ///< absolute: relative_tolerance * model_size
  double t_lambda = 0.0, t_star = 0.0, t_mu = 0.0;
  std::size_t samples = 0;
  WorstCase planarity;  ///< distance of a quad's 4th vertex from the plane of the others
  WorstCase isometry;   ///< |length(t) - length(t*)| over edges and face diagonals
  bool closed = false;  ///< a tube: `closure` is meaningful
  WorstCase closure;    ///< |V_{i,N}(t) - V_{i,0}(t)|
  double reproduction = 0.0;  ///< max |evaluate(t*) - constructed net| (input reproduced at t*)
  bool shape_checked = true;  ///< planarity and isometry were measured (CheckOptions::shape)

  bool passed() const;
};

/// Checks the P-hedron at t* only (samples = 1).
IntervalCheckReport check_at_t_star(const PHedron& phedron, double relative_tolerance = tolerance::check_relative);

/// Checks over the whole flexion interval.
IntervalCheckReport check_over_interval(const PHedron& phedron, const CheckOptions& options = {});

/// `samples` evenly spaced parameters of [lo, hi], both ends included exactly.
std::vector<double> interval_samples(double lo, double hi, std::size_t samples);

}  // namespace phedra
