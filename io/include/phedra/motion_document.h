#pragma once
// The motion as JSON (docs/formats.md): a quad mesh, its vertex labels and its
// vertex positions at chosen t. Written for one P-hedron and for assemblies.
//   {"name", "kind", "t_star", "case", "flexion_interval": [lo, hi],
//    "members": [...] (assemblies), "labels": [[i, c] or [member, i, c], ...],
//    "faces": [[a, b, c, d], ...], "face_members": [...] (assemblies),
//    "samples": [{"t": T, "vertices": [[x, y, z], ...]}, ...]}

#include "phedra/design.h"
#include "phedra/grid_topology.h"
#include "phedra/vector_types.h"

#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <vector>

namespace phedra {

class PHedron;

struct MotionDocument {
  std::string name;
  std::string kind;
  double t_star = 0.0;
  std::string motion_case;
  double t_lambda = 0.0, t_mu = 0.0;
  std::vector<std::string> members;             ///< empty for a single P-hedron
  std::vector<std::vector<std::size_t>> labels;  ///< one per vertex
  std::vector<Quad> faces;
  std::vector<std::size_t> face_members;        ///< empty for a single P-hedron
  /// Fills the positions of every vertex at t (throws outside the interval).
  std::function<void(double, Points&)> positions;
  /// Written as "buildability" when not null (what every export says of the design).
  nlohmann::json buildability;
};

/// The document of one P-hedron: labels [i, c] in its grid.
MotionDocument motion_document(const PHedron& phedron);

/// The motion document of a design: one P-hedron keeps labels [i, c]; an
/// assembly gets labels [member, i, c], member names and face members, over its
/// separate or (with merge) merged mesh.
MotionDocument motion_document(const Design& design);

/// The JSON text for the given t. Throws Error(internal) rather than write a
/// non-finite number.
std::string motion_json(const MotionDocument& document, const std::vector<double>& ts);

}  // namespace phedra
