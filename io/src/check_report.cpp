#include "phedra/check_report.h"

#include "phedra/number_format.h"

#include <ostream>

namespace phedra {

nlohmann::json worst_case_json(const WorstCase& w, double size) {
  return {{"value", w.value}, {"relative", size > 0 ? w.value / size : w.value}, {"t", w.t}, {"where", w.location}};
}

void print_worst_case(std::ostream& out, const char* name, const WorstCase& w, double size) {
  out << "  " << name << format_human(w.value) << " (" << format_human(w.value / size)
      << " of the model size) at t = " << format_human(w.t) << (w.location.empty() ? "" : ", " + w.location) << '\n';
}

nlohmann::json report_json(const IntervalCheckReport& r) {
  nlohmann::json j{{"passed", r.passed()},
                   {"model_size", r.model_size},
                   {"tolerance", r.tolerance},
                   {"flexion_interval", {r.t_lambda, r.t_mu}},
                   {"t_star", r.t_star},
                   {"samples", r.samples},
                   {"planarity", r.shape_checked ? worst_case_json(r.planarity, r.model_size) : nlohmann::json()},
                   {"isometry", r.shape_checked ? worst_case_json(r.isometry, r.model_size) : nlohmann::json()},
                   {"reproduction", r.reproduction}};
  if (r.closed) j["closure"] = worst_case_json(r.closure, r.model_size);
  return j;
}

std::ostream& operator<<(std::ostream& out, const IntervalCheckReport& r) {
  out << (r.passed() ? "PASS" : "FAIL") << ": " << r.samples << " configurations over [" << format_human(r.t_lambda)
      << ", " << format_human(r.t_mu) << "], tolerance " << format_human(r.tolerance) << " (model size "
      << format_human(r.model_size) << ")\n";
  print_worst_case(out, "planarity    ", r.planarity, r.model_size);
  print_worst_case(out, "isometry     ", r.isometry, r.model_size);
  if (r.closed) print_worst_case(out, "closure gap  ", r.closure, r.model_size);
  out << "  reproduction " << format_human(r.reproduction) << " (evaluate(t*) against the constructed net)\n";
  return out;
}

nlohmann::json report_json(const AssemblyCheckReport& r) {
  nlohmann::json j = report_json(static_cast<const IntervalCheckReport&>(r));
  j["passed"] = r.passed();
  j["name"] = r.name;
  j["members"] = r.members;
  j["shared_vertex_groups"] = r.shared_groups;
  j["shared_vertices"] = worst_case_json(r.shared, r.model_size);
  j["member_closure"] = r.member_closure;
  if (!r.warning.empty()) j["warning"] = r.warning;
  return j;
}

std::ostream& operator<<(std::ostream& out, const AssemblyCheckReport& r) {
  out << "geometry " << (r.passed() ? "PASS" : "FAIL") << ": " << r.name << ", " << r.members << (r.members == 1 ? " member" : " members")
      << ", " << r.samples << " configurations over [" << format_human(r.t_lambda) << ", " << format_human(r.t_mu)
      << "], tolerance " << format_human(r.tolerance) << " (model size " << format_human(r.model_size) << ")\n";
  if (r.shape_checked) {
    print_worst_case(out, "planarity       ", r.planarity, r.model_size);
    print_worst_case(out, "isometry        ", r.isometry, r.model_size);
  } else {
    out << "  planarity, isometry: not checked (--closure-only)\n";
  }
  if (r.closed) print_worst_case(out, "closure gap     ", r.closure, r.model_size);
  if (r.members > 1) {
    out << "  shared vertices: " << r.shared_groups << " groups\n";
    print_worst_case(out, "shared mismatch ", r.shared, r.model_size);
  }
  out << "  reproduction    " << format_human(r.reproduction) << " (evaluate(t*) against the constructed nets)\n";
  if (!r.warning.empty()) out << "  warning: " << r.warning << '\n';
  return out;
}

}  // namespace phedra
