#pragma once
// An assembly of P-hedra that fold with one parameter t (MATH.md section 6):
// member 0 is a P-hedron (open or a tube); every other member is seeded on a
// vertex line of an earlier member. evaluate(t) is evaluate(t) of the base plus
// the recursions of the members, parents before children; the flexion interval
// is the base's (the members' profile planes are the base's).

#include "phedra/net_writer.h"
#include "phedra/phedron.h"
#include "phedra/seeded_member.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace phedra {

/// One vertex of one member.
struct VertexRef {
  std::size_t member = 0;
  std::size_t vertex = 0;  ///< index in the member's topology
  bool operator==(const VertexRef&) const = default;
};

/// Positions of every member at one t (user frame), and the closure gap of each tube.
struct AssemblyConfiguration {
  double t = 0.0;
  std::vector<Points> members;
  std::vector<ClosureGap> closure;
  /// Scratch of evaluate (the members' canonical nets) and of evaluate_rate (their
  /// rates too), kept between calls.
  std::vector<NetState> states, rate_states;
};

class Assembly {
 public:
  explicit Assembly(PHedron base, std::string base_name = "base");

  /// Adds a member seeded on a vertex line of an existing member; returns its index.
  /// Throws InvalidInputError (naming spec.field) when the member violates an assumption.
  std::size_t add_member(const MemberSpec& spec);

  std::size_t member_count() const { return members_.size(); }
  const PHedron& base() const { return base_; }
  const std::string& name() const { return base_.input().name; }
  const std::string& member_name(std::size_t m) const { return members_[m].name; }
  const GridTopology& topology(std::size_t m) const { return members_[m].topology; }
  bool closed(std::size_t m) const { return members_[m].closed; }
  /// The member's positions at t* (user frame, topology order).
  const Points& reference(std::size_t m) const { return members_[m].reference; }
  /// The member's axial and general nets and apex heights at t* (canonical frame,
  /// rows x n without boundary columns): the nets MATH.md section 9 reads panel
  /// shapes from.
  const NetState& reference_state(std::size_t m) const {
    return m == 0 ? base_reference_ : members_[m].seeded->reference_state();
  }
  /// The member's apex heights T_0..T_n at t* (user frame).
  std::vector<double> apex_heights(std::size_t m) const;
  /// The member's sign (members use one sign; the base's first sign).
  Sign sign(std::size_t m) const;
  /// The member's signs s_1..s_{n-1} (the sign of apex S_{j+1} is entry j).
  const std::vector<Sign>& signs(std::size_t m) const;
  /// How member m (>= 1) is attached.
  const Seed& seed(std::size_t m) const { return members_[m].seeded->seed(); }
  std::size_t total_vertex_count() const;

  const FlexionInterval& flexion_interval() const { return base_.flexion_interval(); }
  double t_star() const { return base_.t_star(); }
  double t_at_fraction(double fraction) const { return base_.t_at_fraction(fraction); }
  /// Bounding-box diagonal of every member at t*.
  double model_size() const { return model_size_; }

  /// Positions of all members at t. Throws OutOfIntervalError outside the interval.
  void evaluate(double t, AssemblyConfiguration& out) const;
  /// On a branch of the base (PHedron::evaluate): the members follow it.
  void evaluate(double t, const std::vector<bool>& flipped, AssemblyConfiguration& out) const;
  AssemblyConfiguration evaluate(double t) const;
  /// The positions at t (into `out`) and their exact rates dX/dt, member by
  /// member in topology order (PHedron::evaluate_canonical_rate; the members'
  /// recursions are linear in their parent's state). Returns false at a flexion
  /// limit, where the rates are infinite (`out` is complete then, `rates` not).
  bool evaluate_rate(double t, AssemblyConfiguration& out, std::vector<Points>& rates) const;
  /// The members' canonical nets at t and their rates (what evaluate_rate writes
  /// out), without writing them: `rates` incomplete and false at a flexion limit.
  /// Without `closure`, the closed members' (not the base's) last columns, which
  /// repeat their first ones, are not computed (SeededMember::evaluate).
  bool evaluate_canonical_rate(double t, std::vector<NetState>& states, std::vector<NetState>& rates,
                               bool closure = true) const;
  /// Where a member vertex is in its member's canonical nets: the member, the
  /// entry of the general net it is (or starts from), and for an open net's
  /// boundary columns the apex it reaches (1: S_0, 2: S_n; 0: none).
  struct NetPlace {
    std::uint32_t member = 0, entry = 0, boundary = 0;
  };
  std::vector<NetPlace> net_places(std::span<const VertexRef> vertices) const;
  /// The user-frame positions (Kind::rates: rates) of the vertices at `places`
  /// from the canonical nets (or their rates) evaluate_canonical_rate gives.
  void write_vertices(const std::vector<NetState>& states, std::span<const NetPlace> places, Points& out,
                      NetWriter::Kind kind = NetWriter::Kind::positions) const;

  /// Samples evaluated together (SIMD across samples; assembly_lanes.cpp).
  static constexpr std::size_t lanes = NetLanes::lanes;
  /// Scratch of vertices_lanes, kept between calls.
  struct LaneScratch {
    NetState base_state, base_rate;  ///< the base's nets, one sample at a time
    NetLanes base, base_rates;       ///< the base's nets of the lanes
    std::vector<double> rows, apexes;  ///< the members' last two rows and their apexes
    std::vector<std::size_t> columns, offset;
  };
  /// Places grouped by their row: order[first[i] .. first[i + 1]) are row i's;
  /// and for each member (not the base) the columns j >= 1 of its general net
  /// that anything reads (a place, or a child's seed line), ascending: the lanes'
  /// recursions make no other (a vertex line coupled members share is read from
  /// one of them).
  struct RowPlaces {
    std::vector<std::uint32_t> order;
    std::vector<std::size_t> first;
    std::vector<std::vector<std::uint32_t>> general_columns;
  };
  RowPlaces places_by_row(std::span<const NetPlace> places) const;
  /// The vertices at `places` (grouped by places_by_row) of `lanes` samples ts[0..lanes) at once, positions
  /// into `x` and rates into `v`, [place][coordinate][lane]: for each lane what
  /// write_vertices writes from evaluate_canonical_rate (without closure) of its
  /// sample, bit for bit. The base's nets one sample at a time, then the members'
  /// recursions of all lanes together, row by row across the members (two rows
  /// of each in the caches, not whole nets). False when a sample is at a flexion
  /// limit (no rates).
  bool vertices_lanes(const double* ts, std::span<const NetPlace> places, const RowPlaces& by_row, double* x,
                      double* v, LaneScratch& scratch) const;

  /// Groups of vertices of different members that coincide at t* (within 1e-9 of
  /// the model size): the vertices the couplings share. They must stay together.
  const std::vector<std::vector<VertexRef>>& shared_vertices() const;

 private:
  struct Member {
    std::string name;
    bool closed = false;
    GridTopology topology;
    Points reference;
    std::optional<SeededMember> seeded;  ///< empty for the base
  };
  void evaluate_states(double t, std::vector<NetState>& states, const std::vector<bool>* flipped = nullptr) const;
  void evaluate_on(double t, const std::vector<bool>* flipped, AssemblyConfiguration& out) const;
  void write_user(std::size_t m, const NetState& state, Points& out,
                  NetWriter::Kind kind = NetWriter::Kind::positions) const;
  /// out.members and out.closure from out.states.
  void write_configuration(AssemblyConfiguration& out) const;

  PHedron base_;
  NetState base_reference_;
  std::vector<Member> members_;
  double model_size_ = 0.0;
  mutable std::optional<std::vector<std::vector<VertexRef>>> shared_;
};

}  // namespace phedra
