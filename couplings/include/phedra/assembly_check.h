#pragma once
// The closure and compatibility check of an assembly over its whole flexion
// interval (dense samples, both ends and t*): each tube's closure gap, the
// mismatch of vertices shared between members, planarity and isometry of every
// member, each with the worst t, member and vertex.

#include "phedra/assembly.h"
#include "phedra/interval_check.h"

namespace phedra {

/// The figures of IntervalCheckReport over all members (`closed`: some member is a
/// tube; `closure` is the worst tube's gap), plus the shared vertices.
struct AssemblyCheckReport : IntervalCheckReport {
  std::string name;
  std::size_t members = 0;
  std::size_t shared_groups = 0;       ///< groups of coincident vertices checked
  WorstCase shared;                    ///< worst distance between vertices that coincide at t*
  std::vector<double> member_closure;  ///< worst closure gap of each member (0 for open members)
  std::string warning;                 ///< e.g. an anti-parallelogram that violates its symmetry condition

  bool passed() const;
};

AssemblyCheckReport check_assembly(const Assembly& assembly, const CheckOptions& options = {});

/// The same figures at t* only.
AssemblyCheckReport check_assembly_at_t_star(const Assembly& assembly,
                                             double relative_tolerance = tolerance::check_relative);

}  // namespace phedra
