#pragma once
// The mechanics' plots (chart.h): the energy landscape with its equilibria and
// forces, and the smallest modes over the flexion interval with the gap.

#include "phedra/chart.h"
#include "phedra/energy_landscape.h"
#include "phedra/modes_over_interval.h"

namespace phedra {

/// E(t) with the equilibria marked (the rest state, minima, maxima), dE/dt, and
/// the forces that hold an extension along each axis against the stroke
/// (L_k over its rest length).
Chart energy_chart(const EnergyLandscape& landscape);

/// The smallest non-rigid eigenvalues (log), one line per tracked mode,
/// crossings marked; the gap; the first mode's alignment with the motion.
Chart modes_chart(const ModesOverInterval& modes);

}  // namespace phedra
