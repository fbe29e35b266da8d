#pragma once
// The panels of a design at one t as the bar-and-hinge model sees them
// (MERLIN2's definitions, docs/design.md "Mechanics"): the panel mesh's
// vertices within 1e-9 of the model size are one node; a face with the same
// node set as an earlier one (a wall two cells share) is dropped; a quad with
// two adjacent corners on one node is a triangle panel; any other collapse is
// refused (InvalidInputError naming the panel). Nodes are numbered in the order
// the panels first use them.

#include "phedra/design.h"

#include <optional>
#include <vector>

namespace phedra {

/// A panel of the model: a face of the panel mesh.
struct ModelPanel {
  std::size_t face = 0;                ///< its panel number (face of panel_mesh(design))
  std::vector<std::size_t> corners;    ///< 3 or 4 nodes, in the face's order
  /// n5b8: the centre node; it is corners[base] + ratio (corners[base + 2] - corners[base]).
  /// n4b5: the panel is split along corners[base] - corners[base + 2].
  std::optional<std::size_t> centre;
  std::size_t base = 0;
  double ratio = 0.0;
};

struct ModelMesh {
  double t = 0.0;
  std::vector<VertexRef> node_vertex;  ///< each node: a member vertex at it
  Points positions;                    ///< the nodes at t
  std::vector<ModelPanel> panels;
  std::size_t dropped_faces = 0;       ///< walls two cells share, modelled once
  std::size_t triangle_panels = 0;

  /// The nodes in another configuration of the same design, or their rates
  /// from the members' rates (Assembly::evaluate_rate).
  void nodes(const std::vector<Points>& members, Points& out) const;
};

/// The model's mesh of `design` at the configuration `at`.
ModelMesh model_mesh(const Design& design, const AssemblyConfiguration& at);

}  // namespace phedra
