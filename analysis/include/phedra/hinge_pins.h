#pragma once
// Pin hinges for thick plates (issue 27, `--hinge pin`): at every hinge, knuckles
// on the hinge line (the fold line, so the motion is the zero-thickness one,
// unchanged), alternating between its two plates along it, and a pin through
// them. The plates are cut back from the hinge line (ThickPlates' hinge gap, at
// least pin_hinge_gap) so that the other plate's knuckles turn freely. Each
// knuckle is one closed solid: a tube around the hinge line joined to a leaf
// that lies on its own plate's panel face (the side away from the plates), to be
// glued there or merged with the plate by the slicer; each pin a closed
// cylinder.
//
//   profile of a knuckle (across the hinge line, its own plate to the right):
//
//            plate side
//        .-""-.
//       /  ()  \____________    <- the panel plane (the plate's bottom face)
//       \      /____________|   <- the leaf, on the plate's panel face
//        '-..-'
//
// Sizes follow the thickness T: knuckle radius T/2, pin radius 0.2 T (its hole
// 0.05 T wider), clearance 0.08 T between parts, leaf 0.3 T thick reaching 2 T
// onto the plate; a knuckle about 3 T long (3 to 15 of them a hinge, an odd
// number, the hinge's ends kept clear by T or a tenth of it).

#include "phedra/thick_plates.h"

#include <array>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace phedra {

struct PinSizes {
  double knuckle_radius = 0.0, pin_radius = 0.0, hole_radius = 0.0, clearance = 0.0;
  double leaf_thickness = 0.0, leaf_reach = 0.0, knuckle_length = 0.0;
  explicit PinSizes(double thickness);
};

/// What a printer makes (millimetres): the profile of `--printer` (issue 38,
/// item 1). The pin hinge parts keep their proportions to the plates'
/// thickness T (the clearances tested in tests/pin_clearance_test.cpp hold for
/// every T), so a printer sets the thinnest plates whose parts it makes.
struct PrinterProfile {
  std::string name;
  double nozzle_mm = 0.4;            ///< the narrowest line it lays (a wall of the knuckle is at least two)
  double smallest_feature_mm = 0.8;  ///< the thinnest wall or leaf it makes
  double clearance_mm = 0.3;         ///< between two parts that must move apart (knuckle and the other plate)
  double pin_mm = 2.0;               ///< the thinnest pin (diameter) that holds
  double gap_mm = 0.4;               ///< the narrowest gap it keeps open (between the knuckles along a hinge)
};
/// FDM: nozzle 0.4 mm, walls 0.8 mm, clearance 0.3 mm, pins 2 mm, gaps 0.4 mm;
/// SLA (resin): 0.05, 0.3, 0.15, 1 and 0.2 mm.
PrinterProfile fdm_printer();
PrinterProfile sla_printer();

/// The thinnest plates (mm) whose pin hinge parts `printer` makes: each size of
/// PinSizes at least what it asks (pin 0.4 T >= pin_mm, clearance 0.08 T >=
/// clearance_mm, the knuckles' gap 0.08 T >= gap_mm, the knuckle's wall 0.25 T
/// and the leaf 0.3 T >= smallest_feature_mm and >= 2 nozzle_mm, the pin's play
/// in its hole 0.05 T >= half the clearance, or the whole of it printed in
/// place); `binding` names the size that sets it.
double thinnest_printable_mm(const PrinterProfile& printer, std::string* binding = nullptr, bool in_place = false);

/// The hinge gap pin hinges need at thickness T: both plates clear of a knuckle
/// turning about the hinge line, with the clearance.
double pin_hinge_gap(double thickness);

struct HingeParts {
  std::vector<Solid> solids;       ///< knuckles, then pins
  std::vector<std::string> names;  ///< knuckle_<a>_<b>_<k> (of plate panel a, on its hinge with b), pin_<a>_<b>
  /// The panel whose plate each part moves with: a knuckle's own, a pin's the
  /// first (a); printed in place, the pin is one with that plate's knuckles.
  std::vector<std::size_t> body;
  std::size_t hinges = 0, knuckles = 0, pins = 0;
};

/// Where each hinge's knuckles and pin start and end: a margin from each end of
/// the hinge (model units), at first a tenth of its length but at most T, grown
/// (by half of itself, at least T/2, up to 16 rounds) at every end where a part
/// of the hinge cuts into a part of another hinge or into a plate other than its
/// own at one of the configurations `ts` (pin_configurations: t* and the thick
/// interval; hinges that meet at a vertex then keep their knuckles apart). A hinge whose
/// margins leave no room has no knuckles and no pin.
struct PinLayout {
  std::map<std::pair<std::size_t, std::size_t>, std::array<double, 2>> margins;  ///< mesh edge (lower vertex first) -> {at it, at the other}
  bool in_place = false;             ///< printed in place (InPlace): a pin is one with its first plate's knuckles
  std::size_t rounds = 0;            ///< rounds of growing the margins taken
  std::size_t without_knuckles = 0;  ///< hinges left without parts
};
/// Printed in place (`generate --print-in-place`): every plate, its knuckles
/// and the pins that are one with them (HingeParts::body) make one body; the
/// bodies are printed together at t, each part at least `clearance` from every
/// part and plate of another body there (the layout grows margins for that too).
struct InPlace {
  double t = 0.0;
  double clearance = 0.0;
};
/// The clearance of parts printed in place: the pin's play in its hole, 0.05 T
/// (the least of the design's clearances between moving parts).
double in_place_clearance(double thickness);
PinLayout pin_layout(const ThickPlates& plates, const std::vector<double>& ts, std::optional<InPlace> in_place = std::nullopt);

/// The configurations pin hinges are laid out and checked at: t*, then
/// `samples` evenly over the thick interval [lower, upper], its ends included
/// (the check takes twice as many less one: the layout's and those half way).
std::vector<double> pin_configurations(double t_star, double lower, double upper, std::size_t samples);
/// The layout's samples (generate adds the t it writes).
constexpr std::size_t pin_layout_samples = 9;

/// Two parts, or a part and a plate, cutting into each other (deeper than 1e-9
/// of the model size) at t: named as generate names them (knuckle_<a>_<b>_<k>,
/// pin_<a>_<b>, plate_<panel>).
struct PinCrossing {
  std::string a, b;
  double t = 0.0, depth = 0.0;
};
/// Every crossing of the parts of `layout` (knuckles, their leaves and pins as
/// the solids generate writes) with each other and with the plates, at each of
/// `ts`; a knuckle and the plate its leaf is glued to, and one hinge's own parts,
/// touch by design and are left out.
std::vector<PinCrossing> pin_crossings(const ThickPlates& plates, const PinLayout& layout, const std::vector<double>& ts);

/// The knuckles and pins of every hinge of `plates` at the mesh positions x
/// (ThickPlates::positions), with the layout's margins. Every solid is closed
/// and outward-oriented. In place, the knuckles of a pin's first plate have no
/// hole (the pin is one with them) and the other plate's turn on it.
HingeParts pin_hinge_parts(const ThickPlates& plates, const Points& x, const PinLayout& layout);

/// Solids of different bodies (plates included) closer than `clearance` at t,
/// printed in place with `layout` (depth: how far apart, 0 touching); one
/// hinge's own parts aside (their clearances are the design's).
std::vector<PinCrossing> pin_gaps(const ThickPlates& plates, const PinLayout& layout, double t, double clearance);

/// The bodies printed in place: plate k with every part that moves with it
/// (HingeParts::body), one solid of several closed shells that touch or
/// overlap (a slicer and 3MF's fill rule take their union), named body_<panel>.
struct InPlaceBodies {
  std::vector<Solid> solids;
  std::vector<std::string> names;
  std::vector<std::size_t> shells;  ///< closed shells in each
};
InPlaceBodies in_place_bodies(const ThickPlates& plates, std::vector<Solid> plate_solids, const HingeParts& parts);

}  // namespace phedra
