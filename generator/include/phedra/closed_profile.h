#pragma once
// Tubes in the core schema (MATH.md section 5): apex heights
// [z_0, ..., z_{N-1}, z_0, z_1] with one sign repeated make every profile a
// closed N-gon (V_{i,N} = V_{i,0}); the mesh then has N cyclic columns and no
// boundary columns. N = 4 gives the parallelogram (all '+') and the
// anti-parallelogram (all '-') tubes.

#include "phedra/control_polylines.h"

namespace phedra {

/// True when the heights repeat their first two at the end (exactly as given),
/// all signs are equal and N = len(apex_heights) - 2 >= 3.
bool has_closed_profile(const ControlPolylines& input);
bool has_closed_profile(const std::vector<double>& heights, const std::vector<Sign>& signs);

/// N, the number of sides of a closed profile (len(apex_heights) - 2).
inline std::size_t closed_profile_sides(const ControlPolylines& input) { return input.apex_heights.size() - 2; }

}  // namespace phedra
