#pragma once
// P-hedral tubes (paper section 4, MATH.md section 5): n = 5 with z_4 = z_0 and
// z_5 = z_1, so every profile is a closed quadrilateral and the mesh has 4
// cyclic columns. The parallelogram tube (all '+') closes over the whole
// flexion interval for any heights; the anti-parallelogram tube (all '-') only
// when z_0 + z_2 = z_1 + z_3 (its symmetry line orthogonal to the axis).

#include "phedra/phedron.h"

#include <array>
#include <optional>
#include <string>

namespace phedra {

enum class TubeType { parallelogram, anti_parallelogram };

const char* to_string(TubeType type);
/// "parallelogram" or "anti-parallelogram"; InvalidInputError naming `field` otherwise.
TubeType tube_type_from_string(const std::string& text, const std::string& field);
/// '+' for parallelograms, '-' for anti-parallelograms.
Sign tube_sign(TubeType type);

/// The four apex heights z_0..z_3 of a tube (user frame).
using TubeHeights = std::array<double, 4>;

/// z_0 + z_2 - (z_1 + z_3): zero for an anti-parallelogram that stays closed.
double symmetry_defect(const TubeHeights& z);

/// Sets the core-schema heights [z_0, z_1, z_2, z_3, z_0, z_1] and four equal signs.
void set_tube_profile(ControlPolylines& input, TubeType type, const TubeHeights& heights);

/// The tube type of an input in the core schema (a closed profile with 4 sides), if any.
std::optional<TubeType> recognise_tube(const ControlPolylines& input);

/// The heights z_0..z_3 of a tube input.
TubeHeights tube_heights(const ControlPolylines& input);

/// For an anti-parallelogram that violates z_0 + z_2 = z_1 + z_3: a sentence with
/// the numbers (it is closed at t* only). Empty otherwise.
std::string tube_symmetry_warning(const ControlPolylines& input);

/// A tube along the trajectory, directions and axis of `base` (its heights and
/// signs are replaced). Throws InvalidInputError for an anti-parallelogram that
/// violates the symmetry condition (with the numbers), and for every violated
/// assumption of the core.
PHedron make_tube(ControlPolylines base, TubeType type, const TubeHeights& heights);

}  // namespace phedra
