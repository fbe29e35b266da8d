#pragma once
// The collision check at t* of a design edited a little at a time: the
// designer's keep-buildable drag (issue 24), which checks every step. It keeps,
// between checks of designs with the same panel mesh, the mesh, its hinges and
// a list of the pairs of panels whose boxes come within a margin of each other,
// each with a certificate: a gap along an axis (either panel's normal, or x,
// y, z) that separates them where they were when the list was made. Panels
// whose corners together have moved less than that gap since cannot meet, and
// pairs not on the list cannot while every corner has moved less than half
// the margin: only the other pairs are tested again, by the narrow phase of
// self_intersection.h. The list is made again when the design moved too far,
// its mesh changed, or its valid panels did.
//
// Whether there is a collision is exactly what self_intersection_at_t_star
// says (the pair it names may be another one).

#include "phedra/design.h"
#include "phedra/self_intersection.h"

#include <cstddef>
#include <memory>
#include <optional>

namespace phedra {

class TStarCollisions {
 public:
  explicit TStarCollisions(const SelfIntersectionOptions& options = {});
  ~TStarCollisions();
  TStarCollisions(TStarCollisions&&) noexcept;
  TStarCollisions& operator=(TStarCollisions&&) noexcept;

  /// The first collision at t* of `design` (a hinge folded shut, or two panels
  /// that cut into each other), as self_intersection_at_t_star.
  std::optional<Collision> check(const Design& design);

  /// What the last check did.
  struct Statistics {
    bool rebuilt = false;        ///< the pair list was made again (first check, another mesh, moved too far)
    std::size_t pairs = 0;       ///< pairs on the list
    std::size_t certified = 0;   ///< of them, kept apart by their certificate
    std::size_t tested = 0;      ///< tested by the narrow phase
  };
  const Statistics& last() const { return last_; }

 private:
  struct State;
  SelfIntersectionOptions options_;
  std::unique_ptr<State> state_;
  Statistics last_;
};

}  // namespace phedra
