#pragma once
// A design: what a preset describes, as an assembly. The core schema gives one
// P-hedron (open, or a tube when its heights close the profile); the keys
// `tube`, `grid`, `row`, `couplings` and `merge` (docs/presets.md) build tubes
// and tube arrays on the same trajectory, directions and axis.

#include "phedra/assembly.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace phedra {

struct Design {
  Assembly assembly;
  /// Output the merged mesh (shared vertices welded, shared face strips deleted).
  bool merge = false;
  /// What it is, for reports: "open P-hedron", "parallelogram tube", "3 x 3 grid of parallelogram cells", ...
  std::string kind;
};

/// From a parsed preset (or reference case) document. InvalidInputError naming the
/// field for every problem.
Design design_from_json(const nlohmann::json& document);

/// Reads, parses and builds a preset file (IOError when unreadable).
Design load_design(const std::filesystem::path& path);

}  // namespace phedra

#include "phedra/assembly_mesh.h"

namespace phedra {

/// The distinct panels of a design: the mesh of every export and report, whose
/// face indices are the panel numbers users see. Shared vertices welded; a wall
/// two members share is one panel of both, or deleted when the preset merges.
AssemblyMesh panel_mesh(const Design& design);

}  // namespace phedra

#include "phedra/motion_document.h"

namespace phedra {

/// The motion document of a design: one P-hedron keeps labels [i, c]; an
/// assembly gets labels [member, i, c], member names and face members, over its
/// separate or (with merge) merged mesh.
MotionDocument motion_document(const Design& design);

}  // namespace phedra
