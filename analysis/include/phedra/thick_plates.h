#pragma once
// Thick panels (issue 27): each panel becomes a plate of thickness T offset to
// one side of the zero-thickness surface (the offset-panel technique). The
// panel itself is the plate's bottom face, so every hinge stays on its fold
// line and the motion is the zero-thickness motion, unchanged: each plate moves
// rigidly with its panel. Where two plates meet at a hinge, their side faces are
// bevelled (tapered): a side face through the hinge line leans by the bevel
// angle from its panel, chosen so that the two plates touch only when the
// hinge's opening on the plate side closes to the smallest it reaches over the
// wanted range (half that opening each when both plates lie in it; 90 degrees,
// square edges, when it never closes below flat). A bevel never lies flatter
// than the floor that keeps the plate's top inset from each edge by at most a
// quarter of the panel's depth behind it: a hinge that closes further limits the
// thick interval instead. Boundary edges are square.
//
// Plates are closed, outward-oriented solids (ThickPlates::solid); for the
// collision test each is a union of convex pieces (a convex panel's plate is
// one; a non-convex panel's is cut along its inner diagonal into two hulls,
// which may reach a little beyond the plate at the cut: conservative).

#include "phedra/assembly_mesh.h"
#include "phedra/buildability.h"
#include "phedra/design.h"
#include "phedra/panel_id.h"

#include <nlohmann/json.hpp>

#include <array>
#include <iosfwd>
#include <algorithm>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace phedra {

/// Which side of the panels the plates lie on: `front` is the side the panel
/// normals of every export point to (right-handed corner order); `automatic`
/// tries both and keeps the one with the wider thick interval (front on a tie).
enum class PlateSide { automatic, front, back };

std::string to_string(PlateSide side);
/// "auto", "front" or "back"; InvalidInputError("--plate-side") otherwise.
PlateSide plate_side_from_string(const std::string& text);

struct ThickOptions {
  double thickness = 0.0;  ///< T, model units (> 0)
  PlateSide side = PlateSide::automatic;
  /// The range the bevels are cut for (default: the zero-thickness buildable interval).
  std::optional<std::pair<double, double>> bevel_range;
  /// Samples from t* to each end of the sweep (crowding towards the end, as the
  /// thin sweep); 0: sweep_samples_for(plates), 200 up to 2000 plates.
  std::size_t samples_per_side = 0;
  /// Penetration that counts, relative to the model size (touching is not a collision).
  double relative_tolerance = 1e-9;
  /// ThickPlates' hinge gap (model units) at `thickness`.
  double hinge_gap = 0.0;
  /// When the gap follows the plates (--hinge pin: pin_hinge_gap, 1.16 T;
  /// --hinge gap without a width: T / 4): at thickness T it is
  /// max(hinge_gap_fixed, hinge_gap_per_thickness T), and the thickest plates
  /// are searched with it so (0: hinge_gap whatever T).
  double hinge_gap_per_thickness = 0.0;
  double hinge_gap_fixed = 0.0;
  double hinge_gap_at(double t) const {
    return hinge_gap_per_thickness > 0.0 ? std::max(hinge_gap_fixed, hinge_gap_per_thickness * t) : hinge_gap;
  }
  /// Also find the thickest plates that fit at t* (ThickReport::thickest).
  bool find_thickest = false;
  /// The thickness was given in millimetres at this scale (--thickness-mm): a
  /// plate that cannot carry it is refused in millimetres, as --thickness-mm.
  std::optional<double> millimetres_per_unit;
};

/// A closed triangle mesh: one plate's solid, outward-oriented.
struct Solid {
  std::vector<Vec3> vertices;
  std::vector<std::array<std::size_t, 3>> triangles;
  double volume() const;
};

/// The plates of a design at one side and thickness; construction does
/// everything that does not depend on t (bevels, the plates in their panels'
/// frames, their convex pieces).
class ThickPlates {
 public:
  /// `side` must be front or back. `range`: the bevel range within the flexion
  /// interval, containing t*. Throws InvalidInputError("--thickness") when T is
  /// not positive and finite, or when a plate's top face vanishes (T too large
  /// for that panel, named).
  /// `hinge_gap` (model units, >= 0): each plate's side faces at its hinges
  /// moved into it by half the gap, so that a gap this wide separates two plates
  /// at each hinge (for a tape, fabric or printed film hinge across it); the
  /// plates' bottoms are then the panels less the gap.
  ThickPlates(const Design& design, double thickness, PlateSide side, std::pair<double, double> range,
              double hinge_gap = 0.0);

  std::size_t plates() const { return plates_.size(); }
  double thickness() const { return thickness_; }
  PlateSide side() const { return side_; }
  /// The panel (mesh face) of plate k.
  std::size_t panel(std::size_t k) const { return plates_[k].face; }
  PanelId panel_id(std::size_t k) const;
  /// Plate corners cut off (two plates that share only that corner overlapped there at t*).
  std::size_t corners_trimmed() const { return corners_trimmed_; }
  /// The smallest bevel angle of any plate edge (radians; pi/2: all square).
  double smallest_bevel() const { return smallest_bevel_; }
  /// Area of the panels with a plate (the zero-thickness area).
  double panel_area() const { return panel_area_; }
  const Design& design() const { return design_; }
  const AssemblyMesh& mesh() const { return mesh_; }

  /// Plate k's panel, bottom (the panel, less the hinge gap) and top faces in
  /// its frame (the panel's corner 0 at the origin, the panel in the xy-plane,
  /// its right-handed normal +z), corner by corner.
  const std::vector<Vec3>& panel_corners(std::size_t k) const { return plates_[k].panel; }
  const std::vector<Vec3>& bottom(std::size_t k) const { return plates_[k].bottom; }
  const std::vector<Vec3>& top(std::size_t k) const { return plates_[k].top; }
  /// Plate k's bevel angle at edge e (corner e to e + 1), radians.
  double bevel(std::size_t k, std::size_t e) const { return plates_[k].bevel[e]; }

  /// Plate k's solid at t (rigidly moved with its panel).
  Solid solid(std::size_t k, double t) const;
  /// Every plate's solid at the mesh positions x (panel_mesh positions at some t).
  std::vector<Solid> solids(const Points& x) const;

  struct Contact {
    std::size_t a = 0, b = 0;  ///< plates
    bool hinge = false;        ///< bevels on a shared hinge, not a penetration of separate plates
    double depth = 0.0;        ///< how far they overlap (a length; for a hinge: the arc at the plates' top)
  };
  /// The first collision at the mesh positions x (openings tracked from `previous`
  /// to `next`, continued as the hinge sweep does), if any.
  std::optional<Contact> collision(const Points& x, const std::vector<double>& previous, std::vector<double>& next) const;
  /// Plate-side openings of every hinge pair at x, in [0, 2 pi).
  std::vector<double> openings(const Points& x) const;
  Points positions(double t) const;

 private:
  struct Piece {
    std::vector<Vec3> points;      ///< in the plate's frame
    std::vector<Vec3> normals;     ///< hull face normals (unit, frame)
    std::vector<Vec3> directions;  ///< hull edge directions (unit, frame)
    Vec3 centre = Vec3::Zero();
    double radius = 0.0;
  };
  struct Plate {
    std::size_t face = 0;
    std::vector<std::size_t> corners;  ///< mesh vertices, 3 or 4 distinct
    std::array<int, 3> anchor{};      ///< corners that fix the frame: origin, along, normal
    std::vector<Vec3> panel, bottom, top;  ///< in the frame (bottom: the panel less the hinge gap)
    std::vector<bool> hinge;          ///< per edge: a hinge (not the boundary)
    std::vector<Piece> pieces;
    std::vector<double> bevel;        ///< per edge k (corner k to k + 1)
    std::vector<double> ceiling;      ///< per edge: the largest bevel t* allows (the floor's cap)
  };
  /// Two plates on one hinge, as seen from plate a: b's panel lies at the
  /// plate-side opening of a; `facing`: b's plate lies in that wedge too.
  struct HingePair {
    std::size_t a = 0, b = 0;
    int edge_a = 0, edge_b = 0;
    bool facing = false;
  };

  Eigen::Matrix3d frame(const Plate& p, const Points& x) const;
  double pair_opening(const HingePair& h, const Points& x) const;
  double sat_depth(const Piece& a, const Eigen::Matrix3d& ra, const Vec3& oa, const Piece& b,
                   const Eigen::Matrix3d& rb, const Vec3& ob) const;

  const Design& design_;
  AssemblyMesh mesh_;
  double thickness_ = 0.0;
  PlateSide side_ = PlateSide::front;
  double tolerance_ = 0.0;
  double smallest_bevel_ = 0.0;
  double panel_area_ = 0.0;
  std::vector<Plate> plates_;
  std::size_t corners_trimmed_ = 0;
  std::vector<HingePair> hinges_;
  std::vector<std::vector<std::size_t>> neighbours_;  ///< per plate: plates on a shared edge
  mutable AssemblyConfiguration configuration_;
};

/// What ends the thick interval on one side.
struct ThickLimit {
  enum class Kind { plates, hinge, thin };
  Kind kind = Kind::plates;  ///< thin: the zero-thickness buildable interval ends first
  PanelId a, b;
  double t = 0.0;
};

struct ThickReport {
  double thickness = 0.0;
  PlateSide side = PlateSide::front;
  double t_star = 0.0, t_lambda = 0.0, t_mu = 0.0;
  double bevel_lower = 0.0, bevel_upper = 0.0;  ///< the range the bevels are cut for
  /// The thick plates collide at t* itself (the plates named); then no interval.
  std::optional<ThickLimit> at_t_star;
  double thick_lower = 0.0, thick_upper = 0.0;  ///< the collision-free interval of the plates around t*
  std::optional<ThickLimit> lower, upper;       ///< what ends it (empty: the flexion limit)
  std::size_t plates = 0, samples = 0, members = 1;
  double smallest_bevel = 0.0;  ///< radians
  double volume = 0.0, panel_area = 0.0;
  double hinge_gap = 0.0;
  /// With find_thickest: the thickest plates that fit at t* (a top face on
  /// every plate, none colliding there, each thickness with its own hinge gap:
  /// ThickOptions::hinge_gap_at), to 1 %; 0 when none does. On `thickest_side`:
  /// this side, or with PlateSide::automatic the side that carries the thicker
  /// ones (the figure does not depend on the thickness asked for).
  std::optional<double> thickest;
  PlateSide thickest_side = PlateSide::front;
  bool collision_free_at_t_star() const { return !at_t_star; }
  nlohmann::json to_json() const;
};

std::ostream& operator<<(std::ostream& out, const ThickReport& report);

/// The thick interval: plates built for the side (both, `automatic`), swept from
/// t* within the zero-thickness buildable interval of `thin` (which the plates
/// cannot exceed: their bottoms are the panels), each end bisected to 1e-12 of
/// the flexion interval. Throws InvalidInputError("--thickness") when the design
/// is not buildable at t* without thickness (nothing to thicken).
ThickReport check_thickness(const Design& design, const BuildabilityReport& thin, const ThickOptions& options);

/// The plates check_thickness chose (its report's side and bevel range).
ThickPlates thick_plates(const Design& design, const ThickReport& report);

/// The part of the flexion interval a report's plates move over (0 when they collide at t*).
double thick_fraction(const ThickReport& report);

/// The thickest plates whose thick interval covers at least `fraction` of the
/// flexion interval (what to suggest when the plates asked for hardly fold).
struct ThickFolding {
  double thickness = 0.0;  ///< model units, to 2 %
  PlateSide side = PlateSide::front;
  double fraction = 0.0;   ///< the part they move over
};
/// A bisection of the thickness's logarithm between 1e-4 of the model size and
/// the thickest plates that fit at t*, on options.side (both with automatic),
/// each thickness with its own hinge gap; none when even the thinnest do not
/// cover `fraction`. About twenty thick sweeps: for the few designs that need it.
std::optional<ThickFolding> thickest_folding(const Design& design, const BuildabilityReport& thin, const ThickOptions& options,
                                             double fraction);

}  // namespace phedra
