#include "phedra/interval_check.h"

#include "phedra/errors.h"
#include "phedra/geometry_checks.h"
#include "phedra/number_format.h"

#include <algorithm>
#include <cmath>
#include <ostream>

namespace phedra {
namespace {

std::string label(const GridTopology& g, std::size_t vertex) {
  return "(" + std::to_string(g.row_of(vertex)) + "," + std::to_string(g.column_of(vertex)) + ")";
}

std::string face_label(const GridTopology& g, std::size_t face) {
  return "face " + label(g, g.faces()[face][0]);
}

std::string segment_label(const GridTopology& g, std::size_t k) {
  const bool diagonal = k >= g.edges().size();
  const Segment& s = diagonal ? g.diagonals()[k - g.edges().size()] : g.edges()[k];
  return std::string(diagonal ? "diagonal " : "edge ") + label(g, s[0]) + "-" + label(g, s[1]);
}

class Checker {
 public:
  Checker(const PHedron& p, double relative) : p_(p), positions_(p.vertex_count()) {
    const GridTopology& g = p.topology();
    segments_ = g.edges();
    segments_.insert(segments_.end(), g.diagonals().begin(), g.diagonals().end());
    reference_lengths_ = segment_lengths(segments_, p.reference());
    report_.model_size = p.model_size();
    report_.tolerance = relative * p.model_size();
    report_.t_lambda = p.flexion_interval().lower.t;
    report_.t_mu = p.flexion_interval().upper.t;
    report_.t_star = p.t_star();
  }

  void sample(double t) {
    p_.evaluate(t, positions_);
    const Deviation flat = planarity(p_.topology().faces(), positions_);
    if (!(flat.value <= report_.planarity.value)) {
      report_.planarity = {flat.value, t, face_label(p_.topology(), flat.index)};
    }
    const Deviation iso = length_deviation(segments_, reference_lengths_, positions_);
    if (!(iso.value <= report_.isometry.value)) {
      report_.isometry = {iso.value, t, segment_label(p_.topology(), iso.index)};
    }
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

  IntervalCheckReport report() const { return report_; }

 private:
  const PHedron& p_;
  Points positions_;
  std::vector<Segment> segments_;
  std::vector<double> reference_lengths_;
  IntervalCheckReport report_;
};

nlohmann::json worst_json(const WorstCase& w, double size) {
  return {{"value", w.value}, {"relative", size > 0 ? w.value / size : w.value}, {"t", w.t},
          {"where", w.location}};
}

}  // namespace

bool IntervalCheckReport::passed() const {
  return planarity.value <= tolerance && isometry.value <= tolerance && reproduction <= tolerance;
}

nlohmann::json IntervalCheckReport::to_json() const {
  return {{"passed", passed()},
          {"model_size", model_size},
          {"tolerance", tolerance},
          {"flexion_interval", {t_lambda, t_mu}},
          {"t_star", t_star},
          {"samples", samples},
          {"planarity", worst_json(planarity, model_size)},
          {"isometry", worst_json(isometry, model_size)},
          {"reproduction", reproduction}};
}

std::ostream& operator<<(std::ostream& out, const IntervalCheckReport& r) {
  auto line = [&](const char* name, const WorstCase& w) {
    out << "  " << name << format_number(w.value) << " (" << format_number(w.value / r.model_size)
        << " of the model size) at t = " << format_number(w.t) << ", " << w.location << '\n';
  };
  out << (r.passed() ? "PASS" : "FAIL") << ": " << r.samples << " configurations over [" << format_number(r.t_lambda)
      << ", " << format_number(r.t_mu) << "], tolerance " << format_number(r.tolerance) << " (model size "
      << format_number(r.model_size) << ")\n";
  line("planarity    ", r.planarity);
  line("isometry     ", r.isometry);
  out << "  reproduction " << format_number(r.reproduction) << " (evaluate(t*) against the constructed net)\n";
  return out;
}

IntervalCheckReport check_at_t_star(const PHedron& p, double relative) {
  Checker checker(p, relative);
  checker.sample(p.t_star());
  checker.reproduction();
  return checker.report();
}

IntervalCheckReport check_over_interval(const PHedron& p, const CheckOptions& options) {
  if (options.samples < 2) {
    throw InvalidInputError("samples", "must be at least 2 (both ends of the interval), got " +
                                           std::to_string(options.samples));
  }
  Checker checker(p, options.relative_tolerance);
  const std::size_t last = options.samples - 1;
  for (std::size_t k = 0; k <= last; ++k) checker.sample(p.t_at_fraction(static_cast<double>(k) / last));
  checker.sample(p.t_star());
  checker.reproduction();
  return checker.report();
}

}  // namespace phedra
