#pragma once
// A small glTF player for tests: poses phedra's animated glTF (either
// representation) at any animation time the way the glTF spec says clients do
// (LINEAR: lerp of translations and morph weights, slerp of rotations) and
// gives every mesh vertex's position, independently of the exporter's code.

#include "phedra/time_map.h"
#include "phedra/vector_types.h"

#include <tiny_gltf.h>

#include <map>
#include <string>
#include <vector>

namespace phedra::test {

class GltfPlayer {
 public:
  /// Parses .glb or .gltf bytes (throws std::runtime_error when tinygltf refuses them).
  explicit GltfPlayer(const std::string& bytes);

  const tinygltf::Model& model() const { return model_; }
  const tinygltf::Value& extras() const { return model_.asset.extras.Get("phedra"); }
  /// How the file says its time maps to t (extras.phedra.time_map, docs/formats.md).
  TimeMap time_map() const;
  /// The last keyframe's time (0 for a static file).
  double duration() const;
  /// Every mesh vertex (glTF frame, Y-up) at animation time `seconds`, indexed as
  /// the exporter's mesh: a morph mesh's vertices in order; node panels through
  /// their extras.vertices. Vertices no panel uses are NaN in the node layout.
  std::vector<Vec3> vertices_at(double seconds, std::size_t vertex_count) const;

 private:
  struct Track {
    std::vector<float> times;
    std::vector<float> values;  ///< components per key: 4 (rotation), 3 (translation), targets (weights)
  };
  std::vector<float> floats(int accessor) const;
  static std::vector<float> sample(const Track& track, std::size_t width, double seconds, bool rotation);

  tinygltf::Model model_;
  std::map<std::pair<int, std::string>, Track> tracks_;  ///< (node, path) -> its channel
};

}  // namespace phedra::test
