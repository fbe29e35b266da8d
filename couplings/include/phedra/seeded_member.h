#pragma once
// A member of an assembly seeded on a vertex line of its parent (MATH.md
// section 6): its trajectory is the parent's vertex line k, its first two
// apexes are the parent's S_k, S_{k+1} (either order), so it moves with the
// parent under the same t with no solving: its other apexes follow from the
// L_0 recursion started at the shared vertex, its vertices from the constant
// ratios, and its general net is the parallel net seeded on the parent's
// general vertex line.

#include "phedra/canonical_frame.h"
#include "phedra/grid_topology.h"
#include "phedra/net_motion.h"

#include <string>
#include <span>
#include <vector>

namespace phedra {

/// The canonical nets of samples evaluated together (SIMD across samples): each
/// number of a NetState the lanes' side by side, [entry][coordinate][lane], and
/// the apexes [j][lane]. Each lane holds what the NetState of its sample holds, bit for bit.
struct NetLanes {
  static constexpr std::size_t lanes = 4;
  std::vector<double> axial, general, apexes;
};

/// Where a member is attached.
struct Seed {
  std::size_t parent = 0;       ///< index of the parent member
  std::size_t vertex_line = 0;  ///< k: the parent's profile vertex V_{i,k} the member starts at
  bool swapped = false;         ///< first two apexes (S_{k+1}, S_k) instead of (S_k, S_{k+1})
  /// The parent's apexes that are the member's first two.
  std::size_t first_apex() const { return swapped ? vertex_line + 1 : vertex_line; }
  std::size_t second_apex() const { return swapped ? vertex_line : vertex_line + 1; }
};

/// A member's own choices: apexes after the first two, and its signs.
struct MemberSpec {
  std::string name;
  Seed seed;
  /// T_2, ..., user heights. With `closed`, T_0 and T_1 are appended, so a quad
  /// tube gives two heights [T_2, T_3].
  std::vector<double> further_heights;
  Sign sign = Sign::plus;  ///< every sign of the member (tubes and arrays use one sign)
  bool closed = true;
  /// The preset field to name in errors (for example "couplings[2]").
  std::string field;
};

class SeededMember {
 public:
  /// `parent_reference` is the parent's state at t*, `parent_heights` its canonical
  /// apex heights, `directions` the canonical profile directions of the assembly.
  /// Throws InvalidInputError (field = spec.field) for violated assumptions.
  SeededMember(const MemberSpec& spec, const NetState& parent_reference, std::size_t parent_columns,
               const Points& directions, const CanonicalFrame& frame, double scale);

  const Seed& seed() const { return seed_; }
  bool closed() const { return closed_; }
  std::size_t columns() const { return motion_.columns(); }
  const std::vector<double>& heights() const { return heights_; }  ///< canonical T_0..T_n
  const std::vector<Sign>& signs() const { return signs_; }
  const NetState& reference_state() const { return reference_; }

  /// The member's state at t from its parent's state at t. Without `closure`, a
  /// closed member's last column (its first again, where the closure is measured)
  /// is not computed: its rows past the first keep whatever they held.
  void evaluate(const NetState& parent, std::size_t parent_columns, NetState& out, bool closure = true) const;
  /// evaluate() of NetLanes::lanes samples at once, a row at a time
  /// (assembly_lanes.cpp; each number the lanes' side by side): row 0 of the
  /// axial and general nets and the apexes from the parent's apexes and its
  /// vertex on the seed's line in row 0,
  void first_row_lanes(const double* parent_apexes, const double* parent_vertex, double* apexes, double* axial,
                       double* general) const;
  /// and row i >= 1 from the apexes, the parent's axial and general vertices on
  /// the seed's line in row i and this member's row i - 1: the axial row whole,
  /// the general one at column 0 and `general_columns` (ascending, >= 1; a column
  /// past the row's last is not made).
  void row_lanes(std::size_t i, const double* apexes, const double* parent_axial, const double* parent_general,
                 const double* previous_axial, const double* previous_general, double* axial, double* general,
                 bool closure, std::span<const std::uint32_t> general_columns) const;

 private:
  Seed seed_;
  bool closed_ = true;
  std::vector<double> heights_;
  std::vector<Sign> signs_;
  NetMotion motion_;
  NetState reference_;
};

}  // namespace phedra
