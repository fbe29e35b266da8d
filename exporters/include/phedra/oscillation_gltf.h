#pragma once
// A mesh oscillating along displacement fields, as an animated glTF that
// three.js and Blender play: the stiffness's modes of `phedra mechanics -o`.
// Each field is two morph targets (+ and - its displacement: weights stay in
// [0, 1], which every client keeps); one animation plays the fields one after
// another, each one full oscillation x + sin(2 pi s) d. Y-up as every export.

#include "phedra/vector_types.h"

#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace phedra {

struct OscillationField {
  std::string name;   ///< the morph targets are "NAME +" and "NAME -"
  Points displacement;  ///< one per position, model units
};

struct OscillationScene {
  std::string name;
  Points positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<OscillationField> fields;
  double seconds = 2.0;   ///< one oscillation
  nlohmann::json extras;  ///< stored as extras.phedra (asset and scene)
};

/// The .glb (binary) or .gltf bytes. Throws Error(internal) rather than store a non-finite number.
std::string oscillation_gltf_bytes(const OscillationScene& scene, bool binary = true);

}  // namespace phedra
