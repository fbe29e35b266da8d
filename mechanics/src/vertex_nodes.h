#pragma once
// Which corner node of the energy's model each member vertex is at (internal
// to mechanics/): the landscape reads the homogenized strain from the nodes,
// each once, with the summed offsets of the member vertices at it
// (HomogenizedStrain::weights), instead of from every member vertex.

#include "phedra/energy_landscape.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace phedra {

/// For every member vertex (members in order, each in topology order) the
/// corner node it is at throughout the motion: within 1e-9 of the model size
/// at the rest state and at 0.23 and 0.71 of the flexion interval (coupled
/// members' shared vertices, and vertices that meet at every t, are one
/// node). None when some vertex is at no node.
std::optional<std::vector<std::uint32_t>> vertex_nodes(const FoldEnergy& fold, double rest_t);

}  // namespace phedra
