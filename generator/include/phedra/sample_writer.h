#pragma once
// The `sample` JSON: labels, faces and vertex positions at chosen t
// (docs/formats.md):
//   {"name", "t_star", "case", "flexion_interval": [lo, hi],
//    "labels": [[i, c], ...], "faces": [[a, b, c, d], ...],
//    "samples": [{"t": T, "vertices": [[x, y, z], ...]}, ...]}

#include "phedra/phedron.h"

#include <string>
#include <vector>

namespace phedra {

/// The sample document for the given t (each inside the flexion interval).
/// Throws Error(internal) rather than write a non-finite number.
std::string sample_json(const PHedron& phedron, const std::vector<double>& ts);

}  // namespace phedra
