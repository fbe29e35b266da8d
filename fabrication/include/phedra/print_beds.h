#pragma once
// Parts laid flat for printing (issue 38, item 3): every solid turned onto the
// flat face that has the whole part above it and leaves the least overhang
// (faces looking down more steeply than 45 degrees), the largest such face: a
// plate on its bottom, the panel's face; a knuckle or a pin on its end, so that
// its round profile is printed layer by layer), turned about the vertical to its
// smallest box, and nested on printer beds by its footprint (the 1 mm cells of
// the cut sheets' nesting, sheet_nesting.cpp): no support is needed, and every
// part touches the bed.

#include "phedra/cut_sheets.h"
#include "phedra/thick_plates.h"

#include <string>
#include <vector>

namespace phedra {

/// A part on its bed: millimetres, the bed's corner at the origin, z up.
struct PrintPart {
  std::string name;
  Solid solid;
  double base_area = 0.0;  ///< mm^2 of the face it lies on (at z = 0)
  std::size_t bed = 0;     ///< which bed, from 0
};

struct PrintLayout {
  Vec2 bed = Vec2(200.0, 200.0);  ///< mm
  double gap = 5.0;               ///< mm between parts and from the bed's edges
  std::vector<PrintPart> parts;   ///< in the order given
  std::size_t beds = 0;
  /// The parts on bed k, in the order given.
  std::vector<const PrintPart*> on_bed(std::size_t k) const;
};

/// "WxH" in mm (e.g. "200x200", "250x210"): a printer's bed. Throws
/// InvalidInputError("--bed") unless both are numbers from 10 to 10^4 mm.
Vec2 bed_size_from_string(const std::string& text);

/// `solids` (mm, any pose; closed and outward, as ThickPlates and the pin hinges
/// give them) laid flat and nested on as many beds of `bed` mm as they need,
/// `gap` mm apart and from the edges, the largest first, each on the first bed
/// with room. `names[k]` names solid k (in errors too). Throws
/// InvalidInputError("--bed") naming the first part that fits no bed, with its
/// size and the bed it would need.
PrintLayout lay_flat(const std::vector<Solid>& solids, const std::vector<std::string>& names, Vec2 bed, double gap = 5.0);

/// The number each panel's plate has on the plate cut sheets (`phedra outlines
/// --thickness-mm`, cut_sheets with CutSheetOptions::plates): by panel, 0 for a
/// panel left off the sheets (oversized, slivers).
std::vector<std::size_t> plate_sheet_numbers(const Design& design);

}  // namespace phedra
