#pragma once
// The user's input: three control polylines (paper, Fig. 1 left), in the
// user's frame. See docs/presets.md for the JSON form.

#include "phedra/vector_types.h"

#include <string>
#include <vector>

namespace phedra {

/// Sign of an inner apex S_1..S_{n-1}: central scaling (+) or perspective
/// collineation (-) between consecutive profile vertices (MATH.md section 2).
enum class Sign { plus, minus };

struct ControlPolylines {
  std::string name = "unnamed";
  /// V_{i,0}, i = 0..m (m >= 1): the trajectory polyline.
  Points trajectory;
  /// d_i = D_i - V_{i,0}, one per trajectory point; non-zero, orthogonal to `axis`.
  Points directions;
  /// Unit direction a of the apex line pi_0 ∩ pi_1 (any direction).
  Vec3 axis = Vec3::UnitZ();
  /// h_j = <S_j, axis>, j = 0..n (n >= 2), with S_j on the line pi_0 ∩ pi_1.
  std::vector<double> apex_heights;
  /// s_1..s_{n-1}: one sign per inner apex.
  std::vector<Sign> signs;
  /// Where the trajectory came from when it was a smooth curve (docs/presets.md),
  /// e.g. "helix, 24 segments, largest chord deviation 0.0093 (tolerance 0.01)"; empty for a polyline.
  std::string trajectory_source;

  std::size_t profile_count() const { return trajectory.size(); }          ///< m + 1
  std::size_t profile_vertex_count() const { return apex_heights.size() - 1; }  ///< n
};

/// "+-+" from signs, and back (throws InvalidInputError naming `signs`).
std::string signs_to_string(const std::vector<Sign>& signs);
std::vector<Sign> signs_from_string(const std::string& text);

}  // namespace phedra
