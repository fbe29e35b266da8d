#include "phedra/interval_check.h"

#include "phedra/errors.h"
#include "phedra/number_format.h"

#include <ostream>

namespace phedra {
namespace {

class Checker {
 public:
  Checker(const PHedron& p, double relative)
      : p_(p), positions_(p.vertex_count()), figures_(p.topology(), p.reference()) {
    report_.model_size = p.model_size();
    report_.tolerance = relative * p.model_size();
    report_.t_lambda = p.flexion_interval().lower.t;
    report_.t_mu = p.flexion_interval().upper.t;
    report_.t_star = p.t_star();
    report_.closed = p.closed();
  }

  void sample(double t) {
    ClosureGap gap;
    p_.evaluate(t, positions_, &gap);
    figures_.observe(t, positions_);
    if (p_.closed()) report_.closure.update(gap.value, t, "row " + std::to_string(gap.row));
    ++report_.samples;
  }

  void reproduction() {
    p_.evaluate(p_.t_star(), positions_);
    double worst = 0.0;
    for (std::size_t k = 0; k < positions_.size(); ++k) {
      const double d = (positions_[k] - p_.reference()[k]).norm();
      if (!(d <= worst)) worst = d;
    }
    report_.reproduction = worst;
  }

  IntervalCheckReport report() {
    report_.planarity = figures_.planarity();
    report_.isometry = figures_.isometry();
    return report_;
  }

 private:
  const PHedron& p_;
  Points positions_;
  FigureTracker figures_;
  IntervalCheckReport report_;
};

}  // namespace

std::vector<double> interval_samples(double lo, double hi, std::size_t samples) {
  if (samples < 2) {
    throw InvalidInputError("samples", "must be at least 2 (both ends of the interval), got " + std::to_string(samples));
  }
  std::vector<double> ts(samples);
  const std::size_t last = samples - 1;
  for (std::size_t k = 0; k < last; ++k) ts[k] = lo + (static_cast<double>(k) / static_cast<double>(last)) * (hi - lo);
  ts[last] = hi;
  return ts;
}

nlohmann::json worst_case_json(const WorstCase& w, double size) {
  return {{"value", w.value}, {"relative", size > 0 ? w.value / size : w.value}, {"t", w.t}, {"where", w.location}};
}

void print_worst_case(std::ostream& out, const char* name, const WorstCase& w, double size) {
  out << "  " << name << format_human(w.value) << " (" << format_human(w.value / size)
      << " of the model size) at t = " << format_human(w.t) << (w.location.empty() ? "" : ", " + w.location) << '\n';
}

bool IntervalCheckReport::passed() const {
  return planarity.value <= tolerance && isometry.value <= tolerance && reproduction <= tolerance &&
         (!closed || closure.value <= tolerance);
}

nlohmann::json IntervalCheckReport::to_json() const {
  nlohmann::json j{{"passed", passed()},
                   {"model_size", model_size},
                   {"tolerance", tolerance},
                   {"flexion_interval", {t_lambda, t_mu}},
                   {"t_star", t_star},
                   {"samples", samples},
                   {"planarity", shape_checked ? worst_case_json(planarity, model_size) : nlohmann::json()},
                   {"isometry", shape_checked ? worst_case_json(isometry, model_size) : nlohmann::json()},
                   {"reproduction", reproduction}};
  if (closed) j["closure"] = worst_case_json(closure, model_size);
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

IntervalCheckReport check_at_t_star(const PHedron& p, double relative) {
  Checker checker(p, relative);
  checker.sample(p.t_star());
  checker.reproduction();
  return checker.report();
}

IntervalCheckReport check_over_interval(const PHedron& p, const CheckOptions& options) {
  Checker checker(p, options.relative_tolerance);
  for (double t : interval_samples(p.flexion_interval().lower.t, p.flexion_interval().upper.t, options.samples)) {
    checker.sample(t);
  }
  checker.sample(p.t_star());
  checker.reproduction();
  return checker.report();
}

}  // namespace phedra
