#pragma once
// Random valid control polylines for property tests: a trajectory that rises
// along the axis, random profile directions (consecutive planes at least ~6°
// apart, trajectory edges not nearly parallel to their planes), random apex
// heights (consecutive triples distinct), then a random rigid placement (any
// axis direction).

#include "phedra/control_polylines.h"
#include "phedra/phedron.h"

#include <functional>
#include <optional>

#include <random>

namespace phedra::test {

/// A uniform random number in [lo, hi).
double uniform(std::mt19937_64& rng, double lo, double hi);

struct RandomInputShape {
  std::size_t strips = 5;          ///< m (profiles: m + 1)
  std::size_t profile_vertices = 4;  ///< n (apexes: n + 1)
  std::vector<Sign> signs;         ///< n - 1 signs; empty: random
  bool random_placement = true;    ///< random axis and translation (else axis z, apex line = z-axis)
  double scale = 1.0;              ///< multiplies every length
  /// Smooth design: directions turn by small angles and the trajectory bends
  /// gently, as a designer's surface does; otherwise both turn by large random
  /// angles (irregular designs).
  bool smooth = false;
};

/// One candidate; the caller constructs a PHedron and retries on InvalidInputError
/// (rare: bifurcation-near or scissor-near draws).
ControlPolylines random_input(std::mt19937_64& rng, const RandomInputShape& shape);

/// Whether t* lies at least 1e-5 of the model size away from both flexion limits.
/// Positions are ill-conditioned next to a limit (dV/dt is unbounded); property
/// tests draw again when this fails and count the redraws.
bool well_inside_interval(double t_star, double lower, double upper, double model_size);

/// Constructs P-hedra from `make()` until one is valid and well inside its
/// interval (at most `attempts` draws); counts the draws it rejected.
std::optional<PHedron> draw_phedron(const std::function<ControlPolylines()>& make, int& redrawn, int attempts = 1000);

/// All 2^(n-1) sign patterns of n profile vertices, pattern k: bit b set = '-' at S_{b+1}.
std::vector<Sign> sign_pattern(std::size_t n, std::size_t k);

}  // namespace phedra::test
