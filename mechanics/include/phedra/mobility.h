#pragma once
// The mobility of the rigid-panel model (issue 36, item 5): the compatibility
// matrix C maps node velocities to every bar's elongation rate and every
// bending hinge's angle rate (times its length) of the panels held rigid (each
// quad: its four edges, the shorter diagonal and the bending hinge across it,
// exactly the six constraints that make four nodes one rigid plate; a triangle:
// its edges; fold hinges free). Its null space less the six rigid motions is
// the internal mechanisms, its left null space the states of self-stress.
//
// The tolerance comes from the exact geometry: the configuration is exact to
// rounding, so a mechanism's singular value is at rounding level (about 1e-15
// of the largest), while a stiff direction's is a property of the shape. The
// count takes singular values under 1e-9 of the largest and reports the gap
// between the two sides of that line.

#include "phedra/model_mesh.h"

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <iosfwd>

#include <optional>
#include <vector>

namespace phedra {

struct Mobility {
  std::size_t nodes = 0;            ///< corner nodes (3 velocity components each)
  std::size_t constraints = 0;      ///< rows of C: bars and bending hinges
  std::size_t internal_mechanisms = 0;
  std::size_t self_stress_states = 0;
  /// The smallest singular values over the largest, ascending (the null space's first),
  /// the rigid motions' six excluded.
  std::vector<double> singular_values;
  double largest_zero = 0.0;        ///< the largest relative singular value counted as zero (0: none)
  double smallest_nonzero = 0.0;    ///< the smallest one above the line
  /// The exact velocity against the mechanisms (none at a flexion limit):
  std::optional<double> motion_in_mechanisms;  ///< |projection of v onto the mechanisms| / |v| (1: v is one)
  std::optional<double> motion_residual;       ///< |C v| / (|C| |v|): 0 when v keeps the panels rigid
  /// Whether the count is sound: the gap is at least 1e4.
  bool clear() const { return smallest_nonzero == 0.0 || largest_zero == 0.0 || smallest_nonzero > 1e4 * largest_zero; }
  nlohmann::json to_json() const;
};

/// Two lines for people: the counts, whether the motion is the mechanism, the singular values' gap.
std::ostream& operator<<(std::ostream& out, const Mobility& m);

/// The relative singular value under which a direction is a mechanism.
inline constexpr double mechanism_threshold = 1e-9;

/// The mobility of the mesh's panels and the velocity of its nodes (3 x nodes), if known.
Mobility mobility(const ModelMesh& mesh, const std::optional<Eigen::VectorXd>& velocity);

/// The mobility of `design` at t, with the exact velocity.
Mobility mobility(const Design& design, double t);

}  // namespace phedra
