#include "phedra/design.h"

#include "phedra/closed_profile.h"
#include "phedra/tube_array.h"

#include <optional>

namespace phedra {
namespace {

std::string profile_kind(const PHedron& p) {
  if (const std::optional<TubeType> type = recognise_tube(p.input())) return std::string(to_string(*type)) + " tube";
  if (p.closed()) return "closed " + std::to_string(closed_profile_sides(p.input())) + "-gon tube";
  return "open P-hedron";
}

}  // namespace

Design single_design(ControlPolylines input) {
  PHedron p(std::move(input));
  const std::string kind = profile_kind(p);
  const std::string name = p.closed() ? "tube" : "P-hedron";
  return {Assembly(std::move(p), name), false, kind};
}

Design tube_design(ControlPolylines input, TubeType type, const TubeHeights& z) {
  PHedron p = make_tube(std::move(input), type, z);
  const std::string kind = profile_kind(p);
  return {Assembly(std::move(p), "tube"), false, kind};
}

Design grid_design(ControlPolylines input, const std::vector<double>& u, const std::vector<double>& w) {
  TubeGrid built = make_parallelogram_grid(std::move(input), u, w);
  const std::string kind = std::to_string(u.size() - 1) + " x " + std::to_string(w.size() - 1) +
                           " grid of parallelogram cells";
  return {std::move(built.assembly), false, kind};
}

AssemblyMesh panel_mesh(const Design& design) {
  return welded_mesh(design.assembly, design.merge ? SharedWalls::remove : SharedWalls::keep_one);
}

bool same_panel_mesh(const Design& a, const Design& b) {
  const Assembly& x = a.assembly;
  const Assembly& y = b.assembly;
  if (a.merge != b.merge || x.member_count() != y.member_count()) return false;
  for (std::size_t m = 0; m < x.member_count(); ++m) {
    const GridTopology& s = x.topology(m);
    const GridTopology& t = y.topology(m);
    if (s.rows() != t.rows() || s.columns() != t.columns() || s.cyclic() != t.cyclic()) return false;
  }
  return x.shared_vertices() == y.shared_vertices();
}

}  // namespace phedra
