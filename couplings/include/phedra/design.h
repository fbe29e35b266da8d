#pragma once
// A design: what a preset describes, as an assembly. The core schema gives one
// P-hedron (open, or a tube when its heights close the profile); the keys
// `tube`, `grid`, `row`, `couplings` and `merge` (docs/presets.md) build tubes
// and tube arrays on the same trajectory, directions and axis. The preset's
// JSON is read by io/ (design_preset.h); the builders here take the geometry.

#include "phedra/assembly.h"
#include "phedra/assembly_mesh.h"
#include "phedra/tube.h"

#include <array>
#include <string>
#include <vector>

namespace phedra {

struct Design {
  Assembly assembly;
  /// Output the merged mesh (shared vertices welded, shared face strips deleted).
  bool merge = false;
  /// What it is, for reports: "open P-hedron", "parallelogram tube", "3 x 3 grid of parallelogram cells", ...
  std::string kind;
};

/// One P-hedron (open, or closed when its heights close the profile), member name
/// "P-hedron" or "tube".
Design single_design(ControlPolylines input);

/// A tube of the given type whose apexes are at heights `z` (make_tube).
Design tube_design(ControlPolylines input, TubeType type, const TubeHeights& z);

/// A grid of parallelogram cells over the u and w heights (make_parallelogram_grid).
Design grid_design(ControlPolylines input, const std::vector<double>& u_heights, const std::vector<double>& w_heights);

/// The distinct panels of a design: the mesh of every export and report, whose
/// face indices are the panel numbers users see. Shared vertices welded; a wall
/// two members share is one panel of both, or deleted when the preset merges.
AssemblyMesh panel_mesh(const Design& design);

/// Whether two designs have the same panel mesh (faces, vertex references, shared
/// walls): the same members' grids, shared vertices and merging; their positions may differ.
bool same_panel_mesh(const Design& a, const Design& b);

}  // namespace phedra
