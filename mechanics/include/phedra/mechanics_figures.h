#pragma once
// The mechanics' figures `phedra optimize` targets (issue 36, item 6), of a
// design as made (t*: its stiffness there, and its energy landscape with the
// folds at rest at t*), with the default model (n5b8 where every panel is
// convex, else n4b5; MERLIN2's manual stiffness):
//   mechanics.gap               second non-rigid eigenvalue over the first, at t*
//   mechanics.motion_stiffness  v^T K v / v^T v of the exact motion at t*
//   mechanics.bistable          two minima over the flexion interval
//   mechanics.barrier           the barrier from the rest state to the other minimum

#include "phedra/bar_hinge_model.h"

#include <optional>
#include <string>
#include <vector>

namespace phedra {

const std::vector<std::string>& mechanics_figure_names();
bool is_mechanics_figure(const std::string& name);

struct MechanicsFigures {
  std::optional<double> gap, motion_stiffness, barrier;
  bool bistable = false;
  /// A continuous measure for a search: positive when one side of the rest
  /// state has E falling (a maximum) and then rising again (a minimum); how far
  /// from that otherwise (negative). dE/dt over (largest E / interval width).
  double bistability = 0.0;
  std::optional<double> figure(const std::string& name) const;
};

/// The model the figures use: n5b8 where every panel is convex at t*, else n4b5;
/// MERLIN2's manual stiffness.
StiffnessOptions default_stiffness(const Design& design);

/// The figures `names` asks for (the stiffness's when gap or motion stiffness,
/// the landscape's when bistable or barrier).
MechanicsFigures mechanics_figures(const Design& design, const std::vector<std::string>& names);

}  // namespace phedra
