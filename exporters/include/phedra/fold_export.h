#pragma once
// FOLD 1.2 (https://github.com/edemaine/fold) of a design: the key frame is the
// design configuration t*, and the motion is `file_frames` (one per given t)
// that inherit the topology (`frame_inherit`) and give `vertices_coords`,
// `edges_foldAngle` (degrees; positive valley, negative mountain; exactly 0 for
// F) and `edges_assignment` (M, V, F for flat hinges, B for boundary edges).
// Vertices that coincide over the whole motion are one vertex (no zero-length
// edge; such a panel is a triangle); shared walls of arrays are one face with
// welded vertices (one connected mesh); a hinge at +-180 keeps the sign it has
// next to it towards t*, so angles are continuous and match the assignment.

#include "phedra/design.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace phedra {

/// How the FOLD file numbers a design's vertices and faces: the panel mesh's
/// vertices (the rows of every other export and of Python's evaluate) that
/// coincide over the whole motion are one FOLD vertex, numbered in the order the
/// faces first use them; a face with two corners at one place is a triangle.
struct FoldNumbering {
  std::vector<std::size_t> vertex;  ///< each panel-mesh vertex's FOLD vertex
  std::vector<std::size_t> kept;    ///< each FOLD vertex's panel-mesh vertex (the first of those at it)
  std::vector<std::vector<std::size_t>> faces;  ///< FOLD's faces_vertices (3 or 4), in panel order
};
FoldNumbering fold_numbering(const Design& design);

/// The FOLD JSON text for the given t (at least one); `buildability` (when not
/// null) is stored as "phedra:buildability". Throws Error(internal) rather than
/// write a non-finite number.
std::string fold_json(const Design& design, const std::vector<double>& ts, const nlohmann::json& buildability = nullptr);

}  // namespace phedra
