#pragma once
// The stiffness's smallest non-rigid modes over the flexion interval (issue 36,
// item 3): at N configurations evenly spread (both limits included), the modes
// tracked from one configuration to the next by their overlap (|cos| of the
// eigenvectors, largest first, 0.5 at least), a crossing flagged where two
// tracked modes change their order.

#include "phedra/stiffness_modes.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace phedra {

struct ModesAt {
  double t = 0.0;
  std::size_t rigid_body_modes = 0;
  std::vector<double> eigenvalues;   ///< ascending
  std::vector<std::size_t> track;    ///< the track of each eigenvalue (1, 2, ...)
  std::optional<double> gap, motion_alignment, motion_stiffness;
};

struct ModeCrossing {
  double after_t = 0.0, before_t = 0.0;  ///< between these two configurations
  std::size_t track_a = 0, track_b = 0;  ///< a was below b before and is above it after
};

struct ModesOverInterval {
  std::string name;
  std::string panels;
  double t_lambda = 0.0, t_mu = 0.0;
  std::vector<ModesAt> configurations;
  std::vector<ModeCrossing> crossings;
  std::size_t tracks = 0;

  nlohmann::json to_json() const;
  std::string to_csv() const;
};

/// `count` (>= 2) configurations, the `modes` smallest non-rigid modes at each.
ModesOverInterval modes_over_interval(const Design& design, std::size_t count, const StiffnessOptions& options,
                                      std::size_t modes);

}  // namespace phedra
