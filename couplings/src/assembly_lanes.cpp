// Samples evaluated together (the energy landscape's walk): the members'
// recursions and the nodes' writes of Assembly::lanes samples at once, each
// number the lanes' side by side, so that one AVX2 instruction does a step of
// all four. Each lane goes through the operations of the one-sample code
// (SeededMember::evaluate, NetMotion, Assembly::write_vertices) in the same
// order; this file is compiled without FMA contraction (couplings/CMakeLists.txt),
// as the one-sample code is (baseline x86-64), so a lane has the same bits.

#include "phedra/assembly.h"
#include "phedra/cpu_clones.h"

#include <algorithm>
#include <cstring>

namespace phedra {
namespace {

constexpr std::size_t L = NetLanes::lanes;
/// Four doubles, one a lane (GCC's and Clang's vector extension), read and
/// written with memcpy (unaligned).
typedef double Four __attribute__((vector_size(L * sizeof(double))));
static_assert(L == 4);

/// One sample's NetState into lane `lane` of `out`.
void put_lane(const NetState& state, std::size_t lane, NetLanes& out) {
  out.axial.resize(3 * L * state.axial.size());
  out.general.resize(3 * L * state.general.size());
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

PHEDRA_CPU_CLONES void SeededMember::evaluate_lanes(const NetLanes& parent, std::size_t parent_columns, NetLanes& out,
                                                    bool closure) const {
  const std::size_t n = motion_.columns();
  const std::size_t count = closed_ && !closure ? n - 1 : n;
  const std::size_t rows = motion_.rows();
  const std::size_t k = seed_.vertex_line;
  const std::size_t entry = 3 * L;  // the numbers of one entry
  out.axial.resize(rows * n * entry);
  out.general.resize(rows * n * entry);
  out.apexes.resize((n + 1) * L);
  double* s = out.apexes.data();
  // NetMotion::complete_first_row.
  std::memcpy(s, &parent.apexes[seed_.first_apex() * L], L * sizeof(double));
  std::memcpy(s + L, &parent.apexes[seed_.second_apex() * L], L * sizeof(double));
  double* row = out.axial.data();
  std::memcpy(row, &parent.axial[k * entry], entry * sizeof(double));
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
  std::copy(out.axial.begin(), out.axial.begin() + static_cast<std::ptrdiff_t>(n * entry), out.general.begin());
  for (std::size_t i = 1; i < rows; ++i) {
    double* axial = out.axial.data() + i * n * entry;
    double* general = out.general.data() + i * n * entry;
    const double* previous_axial = axial - n * entry;
    const double* previous_general = general - n * entry;
    std::memcpy(axial, &parent.axial[(i * parent_columns + k) * entry], entry * sizeof(double));
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
    std::memcpy(general, &parent.general[(i * parent_columns + k) * entry], entry * sizeof(double));
    // NetMotion::advance_general_row from column 1.
    const double* q = motion_.row_scales(i);
    for (std::size_t j = 1; j < count; ++j) {
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
}

bool Assembly::evaluate_canonical_rate_lanes(const double* ts, std::vector<NetLanes>& states,
                                             std::vector<NetLanes>& rates, bool closure, NetState& base_state,
                                             NetState& base_rate) const {
  states.resize(members_.size());
  rates.resize(members_.size());
  for (std::size_t lane = 0; lane < L; ++lane) {
    if (!base_.evaluate_canonical_rate(ts[lane], base_state, base_rate)) return false;
    put_lane(base_state, lane, states[0]);
    put_lane(base_rate, lane, rates[0]);
  }
  for (std::size_t m = 1; m < members_.size(); ++m) {
    const std::size_t parent = members_[m].seeded->seed().parent;
    const std::size_t columns = states[parent].apexes.size() / L - 1;
    members_[m].seeded->evaluate_lanes(states[parent], columns, states[m], closure);
    members_[m].seeded->evaluate_lanes(rates[parent], columns, rates[m], closure);
  }
  return true;
}

PHEDRA_CPU_CLONES void Assembly::write_vertices_lanes(const std::vector<NetLanes>& states,
                                                      std::span<const NetPlace> places, double* out,
                                                      NetWriter::Kind kind) const {
  // write_vertices' arithmetic (NetWriter::user_point): each row of the rotation summed left to right.
  const Mat3 to_user = base_.frame().rotation().transpose();
  const Vec3 origin = kind == NetWriter::Kind::positions ? base_.frame().origin() : Vec3::Zero();
  for (std::size_t k = 0; k < places.size(); ++k, out += 3 * L) {
    const NetPlace& p = places[k];
    const NetLanes& state = states[p.member];
    const double* general = &state.general[p.entry * 3 * L];
    Four gx, gy, gz;
    std::memcpy(&gx, general, sizeof gx);
    std::memcpy(&gy, general + L, sizeof gy);
    std::memcpy(&gz, general + 2 * L, sizeof gz);
    if (p.boundary != 0) {
      const std::size_t apex = p.boundary == 1 ? 0 : state.apexes.size() / L - 1;
      const double* axial = &state.axial[p.entry * 3 * L];
      Four s, ax, ay, az;
      std::memcpy(&s, &state.apexes[apex * L], sizeof s);
      std::memcpy(&ax, axial, sizeof ax);
      std::memcpy(&ay, axial + L, sizeof ay);
      std::memcpy(&az, axial + 2 * L, sizeof az);
      gx = gx + (0.0 - ax);
      gy = gy + (0.0 - ay);
      gz = gz + (s - az);
    }
    for (int c = 0; c < 3; ++c) {
      const Four v = origin[c] + ((to_user(c, 0) * gx + to_user(c, 1) * gy) + to_user(c, 2) * gz);
      std::memcpy(out + c * static_cast<int>(L), &v, sizeof v);
    }
  }
}

}  // namespace phedra
