#include "phedra/tube_array.h"

#include "phedra/coupling.h"
#include "phedra/errors.h"
#include "phedra/number_format.h"

namespace phedra {

std::vector<std::size_t> add_face_coupled_row(Assembly& assembly, std::size_t first, std::size_t side,
                                              const std::vector<double>& free_heights, const std::string& field) {
  if (free_heights.empty()) throw InvalidInputError(field, "a row needs at least one new cell (one free height each)");
  std::vector<std::size_t> added;
  std::size_t parent = first;
  for (std::size_t c = 0; c < free_heights.size(); ++c) {
    MemberSpec spec =
        face_coupling(assembly, parent, c == 0 ? side : 2, free_heights[c], field + ", cell " + std::to_string(c + 1));
    spec.name = "row cell " + std::to_string(c + 1);
    parent = assembly.add_member(spec);
    added.push_back(parent);
  }
  return added;
}

TubeGrid make_parallelogram_grid(ControlPolylines base, const std::vector<double>& u, const std::vector<double>& w) {
  if (u.size() < 2) throw InvalidInputError("grid.u_heights", "needs at least 2 heights (one row of cells)");
  if (w.size() < 2) throw InvalidInputError("grid.w_heights", "needs at least 2 heights (one column of cells)");
  const std::size_t rows = u.size() - 1, columns = w.size() - 1;
  set_tube_profile(base, TubeType::parallelogram, {u[0], w[0], u[1], w[1]});
  TubeGrid grid{Assembly(PHedron(std::move(base)), "cell (0,0)"), {}};
  grid.cell.assign(rows, std::vector<std::size_t>(columns, 0));
  // A cell's errors name the height its far side lies on (the preset's field, its value in the file).
  auto add = [&](std::size_t parent, std::size_t side, double height, std::size_t a, std::size_t b) {
    const std::string name = "cell (" + std::to_string(a) + "," + std::to_string(b) + ")";
    const std::string field = a == 0 ? "grid.w_heights[" + std::to_string(b + 1) + "]" : "grid.u_heights[" + std::to_string(a + 1) + "]";
    try {
      MemberSpec spec = face_coupling(grid.assembly, parent, side, height, "grid " + name);
      spec.name = name;
      grid.cell[a][b] = grid.assembly.add_member(spec);
    } catch (const InvalidInputError& e) {
      if (e.reason().find("coincide") == std::string::npos) throw InvalidInputError(field, name + ": " + e.reason());
      throw InvalidInputError(field, name + ", whose far side lies on this height (" + format_number(height) +
                                         "), would be degenerate: two of its vertex lines coincide; neighbouring "
                                         "heights of grid.u_heights and of grid.w_heights must differ");
    }
  };
  // Column a = 0 along the second family (side 2 of each cell lies on line w[b+1]),
  // then each row along the first family: side 1 of a cell (a = 0) lies on u[1];
  // the cells coupled there have their far side (side 2) on the next line u[a+2].
  for (std::size_t b = 1; b < columns; ++b) add(grid.cell[0][b - 1], 2, w[b + 1], 0, b);
  for (std::size_t b = 0; b < columns; ++b) {
    for (std::size_t a = 1; a < rows; ++a) add(grid.cell[a - 1][b], a == 1 ? 1 : 2, u[a + 1], a, b);
  }
  return grid;
}

}  // namespace phedra
