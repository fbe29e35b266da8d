// Samples evaluated together (the energy landscape's walk): the members'
// recursions and the vertices' writes of Assembly::lanes samples at once, each
// number the lanes' side by side, so that one AVX2 instruction does a step of
// all four; row by row across the members (a member's row i needs its parent's
// row i and its own row i - 1 only), so that two rows of every member stay in
// the caches and only the vertices asked for are written. Each lane goes
// through the operations of the one-sample code (SeededMember::evaluate,
// NetMotion, NetWriter::user_point) in the same order; this file is compiled
// without FMA contraction (couplings/CMakeLists.txt), as the one-sample code is
// (baseline x86-64), so a lane has the same bits.

#include "phedra/assembly.h"
#include "phedra/cpu_clones.h"

#include <algorithm>
#include <cstring>

namespace phedra {
namespace {

constexpr std::size_t L = NetLanes::lanes;
constexpr std::size_t entry = 3 * L;  // the numbers of one net entry (a point's coordinates, each a lane)
/// Four doubles, one a lane (GCC's and Clang's vector extension), read and
/// written with memcpy (unaligned).
typedef double Four __attribute__((vector_size(L * sizeof(double))));
static_assert(L == 4);

/// An entry's numbers from `from` to `to`, four at a time: a copy in smaller
/// pieces (memcpy's 16 bytes) would stall the next step's 32-byte loads of them
/// (no store forwarding from two stores into one load).
[[gnu::always_inline]] inline void copy_entry(const double* from, double* to) {
  for (std::size_t c = 0; c < 3; ++c) {
    Four v;
    std::memcpy(&v, from + c * L, sizeof v);
    std::memcpy(to + c * L, &v, sizeof v);
  }
}

/// One sample's NetState into lane `lane` of `out`.
void put_lane(const NetState& state, std::size_t lane, NetLanes& out) {
  out.axial.resize(entry * state.axial.size());
  out.general.resize(entry * state.general.size());
  out.apexes.resize(L * state.apexes.size());
  for (std::size_t e = 0; e < state.axial.size(); ++e) {
    for (int c = 0; c < 3; ++c) out.axial[(3 * e + static_cast<std::size_t>(c)) * L + lane] = state.axial[e][c];
  }
  for (std::size_t e = 0; e < state.general.size(); ++e) {
    for (int c = 0; c < 3; ++c) out.general[(3 * e + static_cast<std::size_t>(c)) * L + lane] = state.general[e][c];
  }
  for (std::size_t j = 0; j < state.apexes.size(); ++j) out.apexes[j * L + lane] = state.apexes[j];
}

}  // namespace

PHEDRA_CPU_CLONES void SeededMember::first_row_lanes(const double* parent_apexes, const double* parent_vertex,
                                                     double* s, double* row, double* general) const {
  // NetMotion::complete_first_row; the general net's row 0 is the axial one.
  const std::size_t n = motion_.columns();
  std::memcpy(s, parent_apexes + seed_.first_apex() * L, L * sizeof(double));
  std::memcpy(s + L, parent_apexes + seed_.second_apex() * L, L * sizeof(double));
  copy_entry(parent_vertex, row);
  const double* first_ratios = motion_.row_ratios(0);
  const double* mirror = motion_.mirrors();
  for (std::size_t j = 0; j + 1 < n; ++j) {
    const double rho = first_ratios[j];
    Four c, x, y, z, before;
    std::memcpy(&c, s + (j + 1) * L, sizeof c);
    std::memcpy(&x, row + j * entry, sizeof x);
    std::memcpy(&y, row + j * entry + L, sizeof y);
    std::memcpy(&z, row + j * entry + 2 * L, sizeof z);
    std::memcpy(&before, s + j * L, sizeof before);
    const Four nx = rho * x, ny = rho * y, nz = c + rho * (z - c);
    const Four apex = nz + rho * mirror[j] * (before - z);
    std::memcpy(row + (j + 1) * entry, &nx, sizeof nx);
    std::memcpy(row + (j + 1) * entry + L, &ny, sizeof ny);
    std::memcpy(row + (j + 1) * entry + 2 * L, &nz, sizeof nz);
    std::memcpy(s + (j + 2) * L, &apex, sizeof apex);
  }
  for (std::size_t j = 0; j < n; ++j) copy_entry(row + j * entry, general + j * entry);
}

PHEDRA_CPU_CLONES void SeededMember::row_lanes(std::size_t i, const double* s, const double* parent_axial,
                                               const double* parent_general, const double* previous_axial,
                                               const double* previous_general, double* axial, double* general,
                                               bool closure, std::span<const std::uint32_t> general_columns) const {
  const std::size_t n = motion_.columns();
  const std::size_t count = closed_ && !closure ? n - 1 : n;
  copy_entry(parent_axial, axial);
  // NetMotion::fill_row.
  const double* rho = motion_.row_ratios(i);
  for (std::size_t j = 0; j + 1 < count; ++j) {
    Four c, x, y, z;
    std::memcpy(&c, s + (j + 1) * L, sizeof c);
    std::memcpy(&x, axial + j * entry, sizeof x);
    std::memcpy(&y, axial + j * entry + L, sizeof y);
    std::memcpy(&z, axial + j * entry + 2 * L, sizeof z);
    const Four nx = rho[j] * x, ny = rho[j] * y, nz = c + rho[j] * (z - c);
    std::memcpy(axial + (j + 1) * entry, &nx, sizeof nx);
    std::memcpy(axial + (j + 1) * entry + L, &ny, sizeof ny);
    std::memcpy(axial + (j + 1) * entry + 2 * L, &nz, sizeof nz);
  }
  copy_entry(parent_general, general);
  // NetMotion::advance_general_row from column 1, where read (a column's entry
  // needs only its row i - 1 and the axial net's).
  const double* q = motion_.row_scales(i);
  for (const std::uint32_t j : general_columns) {
    if (j >= count) break;
    for (std::size_t c = 0; c < 3; ++c) {
      const std::size_t at = j * entry + c * L;
      Four g, a, b;
      std::memcpy(&g, previous_general + at, sizeof g);
      std::memcpy(&a, axial + at, sizeof a);
      std::memcpy(&b, previous_axial + at, sizeof b);
      const Four next = g + q[j] * (a - b);
      std::memcpy(general + at, &next, sizeof next);
    }
  }
}

PHEDRA_CPU_CLONES bool Assembly::vertices_lanes(const double* ts, std::span<const NetPlace> places,
                                                const RowPlaces& by_row, double* x, double* v,
                                                LaneScratch& scratch) const {
  LaneScratch& s = scratch;
  for (std::size_t lane = 0; lane < L; ++lane) {
    if (!base_.evaluate_canonical_rate(ts[lane], s.base_state, s.base_rate)) return false;
    put_lane(s.base_state, lane, s.base);
    put_lane(s.base_rate, lane, s.base_rates);
  }
  // Each member's columns and place in the row buffers and the apexes (the base's
  // rows and apexes are read from its whole nets).
  const std::size_t members = members_.size(), rows = members_[0].topology.rows();
  std::vector<std::size_t>& columns = s.columns;
  std::vector<std::size_t>& offset = s.offset;  // member m's first entry in a row buffer (its apexes: offset + m)
  columns.assign(members, s.base_state.apexes.size() - 1);
  offset.assign(members + 1, 0);
  for (std::size_t m = 1; m < members; ++m) columns[m] = members_[m].seeded->columns();
  for (std::size_t m = 0; m < members; ++m) offset[m + 1] = offset[m] + (m == 0 ? 0 : columns[m]);
  const std::size_t row_size = offset[members] * entry, apex_size = (offset[members] + members) * L;
  s.rows.resize(8 * row_size);  // rows i - 1 and i of the axial and general nets, positions and rates
  s.apexes.resize(2 * apex_size);
  // kind 0: positions, 1: rates; net 0: axial, 1: general; rows alternate between two buffers.
  auto apexes_of = [&](std::size_t m, std::size_t kind) -> double* {
    return s.apexes.data() + kind * apex_size + (offset[m] + m) * L;
  };
  auto member_row = [&](std::size_t m, std::size_t kind, std::size_t net, std::size_t i) -> double* {
    return s.rows.data() + ((kind * 2 + net) * 2 + (i & 1)) * row_size + offset[m] * entry;
  };
  auto read_apexes = [&](std::size_t m, std::size_t kind) -> const double* {
    return m == 0 ? (kind == 0 ? s.base : s.base_rates).apexes.data() : apexes_of(m, kind);
  };
  auto read_row = [&](std::size_t m, std::size_t kind, std::size_t net, std::size_t i) -> const double* {
    if (m != 0) return member_row(m, kind, net, i);
    const NetLanes& base = kind == 0 ? s.base : s.base_rates;
    return (net == 0 ? base.axial : base.general).data() + i * columns[0] * entry;
  };
  const Mat3 to_user = base_.frame().rotation().transpose();
  for (std::size_t i = 0; i < rows; ++i) {
    for (std::size_t kind = 0; kind < 2; ++kind) {
      for (std::size_t m = 1; m < members; ++m) {
        const SeededMember& member = *members_[m].seeded;
        const std::size_t parent = member.seed().parent, k = member.seed().vertex_line;
        const double* parent_axial = read_row(parent, kind, 0, i) + k * entry;
        if (i == 0) {
          member.first_row_lanes(read_apexes(parent, kind), parent_axial, apexes_of(m, kind), member_row(m, kind, 0, 0),
                                 member_row(m, kind, 1, 0));
        } else {
          member.row_lanes(i, apexes_of(m, kind), parent_axial, read_row(parent, kind, 1, i) + k * entry,
                           member_row(m, kind, 0, i - 1), member_row(m, kind, 1, i - 1), member_row(m, kind, 0, i),
                           member_row(m, kind, 1, i), false, by_row.general_columns[m]);
        }
      }
      // The vertices of row i (Assembly::write_vertices, NetWriter::user_point).
      const Vec3 origin = kind == 0 ? base_.frame().origin() : Vec3::Zero();
      double* out = kind == 0 ? x : v;
      for (std::size_t at = by_row.first[i]; at < by_row.first[i + 1]; ++at) {
        const std::size_t k = by_row.order[at];
        const NetPlace& p = places[k];
        const std::size_t j = p.entry - i * columns[p.member];
        const double* general = read_row(p.member, kind, 1, i) + j * entry;
        Four gx, gy, gz;
        std::memcpy(&gx, general, sizeof gx);
        std::memcpy(&gy, general + L, sizeof gy);
        std::memcpy(&gz, general + 2 * L, sizeof gz);
        if (p.boundary != 0) {
          const double* apex = read_apexes(p.member, kind) + (p.boundary == 1 ? 0 : columns[p.member]) * L;
          const double* axial = read_row(p.member, kind, 0, i) + j * entry;
          Four a, ax, ay, az;
          std::memcpy(&a, apex, sizeof a);
          std::memcpy(&ax, axial, sizeof ax);
          std::memcpy(&ay, axial + L, sizeof ay);
          std::memcpy(&az, axial + 2 * L, sizeof az);
          gx = gx + (0.0 - ax);
          gy = gy + (0.0 - ay);
          gz = gz + (a - az);
        }
        for (int c = 0; c < 3; ++c) {
          const Four w = origin[c] + ((to_user(c, 0) * gx + to_user(c, 1) * gy) + to_user(c, 2) * gz);
          std::memcpy(out + k * entry + static_cast<std::size_t>(c) * L, &w, sizeof w);
        }
      }
    }
  }
  return true;
}

Assembly::RowPlaces Assembly::places_by_row(std::span<const NetPlace> places) const {
  // A counting sort by row (the entry's row in its member's nets).
  const std::size_t rows = members_[0].topology.rows();
  auto row_of = [&](const NetPlace& p) {
    return p.entry / (reference_state(p.member).apexes.size() - 1);
  };
  RowPlaces out;
  out.first.assign(rows + 1, 0);
  for (const NetPlace& p : places) ++out.first[row_of(p) + 1];
  for (std::size_t i = 0; i < rows; ++i) out.first[i + 1] += out.first[i];
  out.order.resize(places.size());
  std::vector<std::size_t> next(out.first.begin(), out.first.end() - 1);
  for (std::size_t k = 0; k < places.size(); ++k) out.order[next[row_of(places[k])]++] = static_cast<std::uint32_t>(k);
  // The general columns read: the places' and the seeds' lines (a child reads its parent's).
  std::vector<std::vector<bool>> read(members_.size());
  for (std::size_t m = 1; m < members_.size(); ++m) read[m].assign(members_[m].seeded->columns() + 1, false);
  for (const NetPlace& p : places) {
    if (p.member != 0) read[p.member][p.entry % members_[p.member].seeded->columns()] = true;
  }
  for (std::size_t m = 1; m < members_.size(); ++m) {
    const Seed& seed = members_[m].seeded->seed();
    if (seed.parent != 0) read[seed.parent][seed.vertex_line] = true;
  }
  out.general_columns.resize(members_.size());
  for (std::size_t m = 1; m < members_.size(); ++m) {
    for (std::size_t j = 1; j < read[m].size(); ++j) {
      if (read[m][j]) out.general_columns[m].push_back(static_cast<std::uint32_t>(j));
    }
  }
  return out;
}

}  // namespace phedra
