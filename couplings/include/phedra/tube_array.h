#pragma once
// Tube arrays (metamaterials) built from couplings (MATH.md section 6).

#include "phedra/assembly.h"
#include "phedra/tube.h"

#include <string>
#include <vector>

namespace phedra {

/// A row of face-coupled parallelogram cells: the first new cell is coupled on
/// `side` of member `first`, each further one on the side opposite its shared
/// side (side 2); one free height per new cell. Returns the new members.
/// (Anti-parallelogram cells have no non-trivial face coupling: see face_coupling.)
std::vector<std::size_t> add_face_coupled_row(Assembly& assembly, std::size_t first, std::size_t side,
                                              const std::vector<double>& free_heights, const std::string& field);

/// A 2D array of parallelogram cells (MATH.md section 6, "2D arrays"): in every
/// profile plane the cells' sides lie on two families of parallel lines, line a of
/// the first family through the apex at height u[a], line b of the second through
/// w[b]. Cell (a, b) is the parallelogram tube with apexes (u[a], w[b], u[a+1], w[b+1]),
/// a < u.size() - 1, b < w.size() - 1; cell (0, 0) runs along the trajectory of
/// `base` (its heights and signs are replaced). Every cell is face-coupled to its
/// neighbours and edge-shares with its diagonal neighbours.
struct TubeGrid {
  Assembly assembly;
  /// cell[a][b]: the member of cell (a, b).
  std::vector<std::vector<std::size_t>> cell;
};
TubeGrid make_parallelogram_grid(ControlPolylines base, const std::vector<double>& u, const std::vector<double>& w);

}  // namespace phedra
