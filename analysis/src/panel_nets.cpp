#include "phedra/panel_nets.h"


namespace phedra {

PanelNets panel_nets(const Assembly& assembly, std::size_t member, std::size_t local) {
  const GridTopology& g = assembly.topology(member);
  const NetState& s = assembly.reference_state(member);
  const std::size_t n = s.apexes.size() - 1;  // net columns (a tube repeats its first two apexes)
  const std::size_t i = local / g.face_columns(), c = local % g.face_columns();
  auto A = [&](std::size_t row, std::size_t j) { return s.axial[row * n + j]; };
  auto G = [&](std::size_t row, std::size_t j) { return s.general[row * n + j]; };
  PanelNets p;
  p.row = i;
  p.net_columns = n;
  if (g.cyclic()) {  // N = n - 1 columns: face c joins net columns c and c + 1
    p.column = c;
    p.axial = {A(i, c), A(i, c + 1), A(i + 1, c + 1), A(i + 1, c)};
    p.general = {G(i, c), G(i, c + 1), G(i + 1, c + 1), G(i + 1, c)};
    return p;
  }
  // Open: column 0 is the boundary towards S_0, 1..n are V_0..V_{n-1}, n + 1 towards S_n.
  if (c == 0 || c == n) {
    const std::size_t j = c == 0 ? 0 : n - 1;
    const Vec3 apex(0.0, 0.0, s.apexes[c == 0 ? 0 : n]);
    const Vec3 b0 = G(i, j) + (apex - A(i, j)), b1 = G(i + 1, j) + (apex - A(i + 1, j));
    p.boundary = true;
    p.column = j;
    if (c == 0) {
      p.axial = {apex, A(i, j), A(i + 1, j), apex};
      p.general = {b0, G(i, j), G(i + 1, j), b1};
    } else {
      p.axial = {A(i, j), apex, apex, A(i + 1, j)};
      p.general = {G(i, j), b0, b1, G(i + 1, j)};
    }
    return p;
  }
  const std::size_t j = c - 1;
  p.column = j;
  p.axial = {A(i, j), A(i, j + 1), A(i + 1, j + 1), A(i + 1, j)};
  p.general = {G(i, j), G(i, j + 1), G(i + 1, j + 1), G(i + 1, j)};
  return p;
}

std::vector<PanelShape> panel_shapes(const Assembly& assembly, const AssemblyMesh& mesh) {
  AssemblyConfiguration c;
  assembly.evaluate(assembly.t_star(), c);
  const Points x = mesh.positions(c);
  std::vector<PanelShape> out;
  out.reserve(mesh.faces.size());
  for (const Quad& q : mesh.faces) out.push_back(panel_shape({x[q[0]], x[q[1]], x[q[2]], x[q[3]]}));
  return out;
}

}  // namespace phedra
