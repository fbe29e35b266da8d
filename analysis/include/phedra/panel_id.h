#pragma once
// A panel named as the user knows it: its number (the face index in
// panel_mesh, the same in every exported file) and where it sits in its
// member's grid.

#include "phedra/assembly_mesh.h"

#include <optional>
#include <string>

namespace phedra {

/// One panel of panel_mesh(design), named as the user knows it.
struct PanelId {
  std::size_t face = 0;    ///< index in panel_mesh: the panel number of every export
  std::size_t member = 0;  ///< the member it belongs to
  std::size_t row = 0;     ///< its strip (profile i to i + 1)
  std::size_t column = 0;  ///< its column in the member's grid
  std::optional<MemberFace> shared_with;  ///< a wall two cells share: the other cell's face
};

/// The panel of face f of a panel mesh.
PanelId panel_id(const Assembly& assembly, const AssemblyMesh& mesh, std::size_t f);

/// "panel 3 (strip 0, column 3)", naming members when there are several and the
/// other cell of a shared wall.
std::string describe(const PanelId& panel, bool several_members);

}  // namespace phedra
