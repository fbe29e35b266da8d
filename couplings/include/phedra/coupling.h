#pragma once
// The two couplings of quad tubes (MATH.md section 6, paper section 4), as
// member specifications for Assembly::add_member.

#include "phedra/assembly.h"

#include <optional>
#include <string>
#include <vector>

namespace phedra {

/// Aligned face coupling on side k (0..3) of the quad tube `parent`: the side
/// V_k V_{k+1}, on the line through S_{k+1}. The new cell is the quad
/// (V_{k+1}, V_k, X, Y) with apexes (S_{k+2}, S_{k+1}, S_k, T): its sides at V_k and
/// V_{k+1} extend the parent's neighbouring sides. T is the one free height of a
/// parallelogram cell. The new cell shares its side 0 with the parent.
/// An anti-parallelogram cell would need T = z_{k+2} + z_k - z_{k+1}, which by the
/// parent's symmetry is z_{k-1}: the cell would be the parent itself, so
/// anti-parallelogram parents are refused (InvalidInputError) with that reason.
MemberSpec face_coupling(const Assembly& assembly, std::size_t parent, std::size_t side,
                         std::optional<double> free_height, const std::string& field);

/// Edge-sharing at vertex k (0..3) of the quad tube `parent`: the new cell starts at
/// V_k with apexes (S_k, S_{k+1}, T_2, T_3), its sides on the lines of the parent's
/// sides there (an X-shaped junction). Parallelogram: free heights [T_2, T_3];
/// anti-parallelogram: [T_2] (T_3 = T_0 + T_2 - T_1 by symmetry).
MemberSpec edge_sharing(const Assembly& assembly, std::size_t parent, std::size_t vertex,
                        const std::vector<double>& free_heights, const std::string& field);

/// After adding an edge-sharing member: its sides must leave V_k on the rays
/// opposite to the parent's sides, otherwise its faces overlap the parent's.
/// InvalidInputError naming `field` otherwise.
void check_edge_sharing_rays(const Assembly& assembly, std::size_t member, const std::string& field);

/// The type of a quad tube member (InvalidInputError naming `field` if it is not one).
Sign quad_tube_sign(const Assembly& assembly, std::size_t member, const std::string& field);

}  // namespace phedra
