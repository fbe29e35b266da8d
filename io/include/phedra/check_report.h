#pragma once
// The JSON and text forms of the geometry checks (interval_check.h,
// assembly_check.h): what `phedra check` and `phedra info` print and write.

#include "phedra/assembly_check.h"
#include "phedra/interval_check.h"

#include <nlohmann/json.hpp>

#include <iosfwd>

namespace phedra {

/// {passed, model_size, tolerance, flexion_interval, t_star, samples, planarity,
/// isometry, reproduction[, closure]}; an assembly's adds name, members,
/// shared_vertex_groups, shared_vertices, member_closure[, warning].
nlohmann::json report_json(const IntervalCheckReport& report);
nlohmann::json report_json(const AssemblyCheckReport& report);

std::ostream& operator<<(std::ostream& out, const IntervalCheckReport& report);
std::ostream& operator<<(std::ostream& out, const AssemblyCheckReport& report);

/// JSON of a worst case: {value, relative, t, where}.
nlohmann::json worst_case_json(const WorstCase& w, double model_size);

/// "  NAME VALUE (REL of the model size) at t = T, WHERE".
void print_worst_case(std::ostream& out, const char* name, const WorstCase& w, double model_size);

}  // namespace phedra
