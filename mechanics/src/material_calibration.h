#pragma once
// MERLIN2's calibration of the bar-and-hinge model from a plate material
// (PrepareData.m, 'auto' mode, n5b8), shared by the model's constructor only.

#include "phedra/bar_hinge_model.h"

namespace phedra {

/// Sets every bar's EA and every hinge's stiffness per unit length from the
/// material: D = E T^3 / (12 (1 - nu^2)); folds k = 1 / (1 / K_L + 1 / K_M) / L
/// with K_L = D / L*, K_M = 0.55 D (L / T)^(1/3); bends k = D (d / T)^(1/3) / d, d
/// the diagonal through the spoke; bar areas per panel (Filipov et al. 2017),
/// summed over the panels that share a bar.
void calibrate_from_material(const Material& material, const std::vector<ModelPanel>& panels, const Points& x,
                             std::vector<Bar>& bars, std::vector<Hinge>& hinges);

}  // namespace phedra
