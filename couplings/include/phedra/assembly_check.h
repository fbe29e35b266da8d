#pragma once
// The closure and compatibility check of an assembly over its whole flexion
// interval (dense samples, both ends and t*): each tube's closure gap, the
// mismatch of vertices shared between members, planarity and isometry of every
// member, each with the worst t, member and vertex.

#include "phedra/assembly.h"
#include "phedra/interval_check.h"

#include <nlohmann/json.hpp>

#include <iosfwd>

namespace phedra {

struct AssemblyCheckReport {
  std::string name;
  std::size_t members = 0;
  std::size_t shared_groups = 0;  ///< groups of coincident vertices checked
  double model_size = 0.0;
  double tolerance = 0.0;
  double t_lambda = 0.0, t_star = 0.0, t_mu = 0.0;
  std::size_t samples = 0;
  WorstCase planarity;
  WorstCase isometry;
  bool has_tubes = false;
  WorstCase closure;       ///< worst tube closure gap
  WorstCase shared;        ///< worst distance between vertices that coincide at t*
  double reproduction = 0.0;  ///< max |evaluate(t*) - constructed net| over all members
  std::vector<double> member_closure;  ///< worst closure gap of each member (0 for open members)
  std::string warning;     ///< e.g. an anti-parallelogram that violates its symmetry condition

  bool passed() const;
  nlohmann::json to_json() const;
};

std::ostream& operator<<(std::ostream& out, const AssemblyCheckReport& report);

AssemblyCheckReport check_assembly(const Assembly& assembly, const CheckOptions& options = {});

/// The same figures at t* only.
AssemblyCheckReport check_assembly_at_t_star(const Assembly& assembly,
                                             double relative_tolerance = tolerance::check_relative);

}  // namespace phedra
