#include "phedra/coupling.h"

#include "phedra/errors.h"
#include "phedra/number_format.h"
#include "phedra/tolerances.h"

#include <cmath>

namespace phedra {
namespace {

void check_index(std::size_t k, const char* what, const std::string& field) {
  if (k > 3) throw InvalidInputError(field, std::string(what) + " must be 0..3 on a quad tube, got " + std::to_string(k));
}

}  // namespace

Sign quad_tube_sign(const Assembly& assembly, std::size_t member, const std::string& field) {
  if (member >= assembly.member_count()) {
    throw InvalidInputError(field, "parent " + std::to_string(member) + " does not exist (there are " +
                                       std::to_string(assembly.member_count()) + " members so far)");
  }
  if (!assembly.closed(member) || assembly.topology(member).columns() != 4) {
    throw InvalidInputError(field, "member " + std::to_string(member) + " (" + assembly.member_name(member) +
                                       ") is not a quad tube; couplings attach to parallelogram or "
                                       "anti-parallelogram tubes");
  }
  return assembly.sign(member);
}

MemberSpec face_coupling(const Assembly& assembly, std::size_t parent, std::size_t side,
                         std::optional<double> free_height, const std::string& field) {
  const Sign sign = quad_tube_sign(assembly, parent, field);
  check_index(side, "side", field);
  const std::vector<double> h = assembly.apex_heights(parent);
  auto S = [&](std::size_t j) { return h[j % 4]; };
  if (sign == Sign::minus) {
    // Symmetry forces T = z_{k+2} + z_k - z_{k+1} = z_{k-1}: the sigma- maps then
    // retrace the parent, and the "new" cell is the parent itself.
    throw InvalidInputError(
        field, "an anti-parallelogram cell face-coupled on side " + std::to_string(side) +
                   " would need T = z_{k+2} + z_k - z_{k+1} = " + format_number(S(side + 2) + S(side) - S(side + 1)) +
                   " = z_{k-1}, which makes it the parent cell itself (the same four vertex lines): anti-parallelogram "
                   "tubes have no non-trivial aligned face coupling; couple them by edge-sharing");
  }
  if (!free_height) throw InvalidInputError(field, "a parallelogram cell needs its free apex height T");
  const double t = *free_height;
  MemberSpec spec;
  spec.field = field;
  spec.seed = {parent, (side + 1) % 4, true};
  spec.further_heights = {S(side), t};
  spec.sign = sign;
  spec.closed = true;
  return spec;
}

MemberSpec edge_sharing(const Assembly& assembly, std::size_t parent, std::size_t vertex,
                        const std::vector<double>& free_heights, const std::string& field) {
  const Sign sign = quad_tube_sign(assembly, parent, field);
  check_index(vertex, "vertex", field);
  const std::vector<double> h = assembly.apex_heights(parent);
  const double t0 = h[vertex % 4], t1 = h[(vertex + 1) % 4];
  MemberSpec spec;
  spec.field = field;
  spec.seed = {parent, vertex, false};
  spec.sign = sign;
  spec.closed = true;
  if (sign == Sign::minus) {
    if (free_heights.size() != 1) {
      throw InvalidInputError(field, "an anti-parallelogram edge-sharing cell takes one free height T_2 (T_3 = T_0 + "
                                     "T_2 - T_1 by symmetry), got " + std::to_string(free_heights.size()));
    }
    spec.further_heights = {free_heights[0], t0 + free_heights[0] - t1};
  } else {
    if (free_heights.size() != 2) {
      throw InvalidInputError(field, "a parallelogram edge-sharing cell takes two free heights [T_2, T_3], got " +
                                         std::to_string(free_heights.size()));
    }
    spec.further_heights = free_heights;
  }
  return spec;
}

void check_edge_sharing_rays(const Assembly& assembly, std::size_t member, const std::string& field) {
  const Seed& seed = assembly.seed(member);
  const Points& parent = assembly.reference(seed.parent);
  const Points& cell = assembly.reference(member);
  const GridTopology& pg = assembly.topology(seed.parent);
  const GridTopology& cg = assembly.topology(member);
  const std::size_t k = seed.vertex_line;
  for (std::size_t i = 0; i < pg.rows(); ++i) {
    const Vec3& v = parent[pg.index(i, k)];
    const Vec3 parent_next = parent[pg.index(i, (k + 1) % 4)] - v;
    const Vec3 parent_previous = parent[pg.index(i, (k + 3) % 4)] - v;
    const Vec3 cell_next = cell[cg.index(i, 1)] - v;
    const Vec3 cell_previous = cell[cg.index(i, 3)] - v;
    if (cell_next.dot(parent_next) >= 0.0 || cell_previous.dot(parent_previous) >= 0.0) {
      throw InvalidInputError(field, "the edge-sharing cell's sides do not leave V_" + std::to_string(k) +
                                         " on the rays opposite to the parent's sides (row " + std::to_string(i) +
                                         "), so its faces overlap the parent's; choose other free heights");
    }
  }
}

}  // namespace phedra
