#include "phedra/interval_check.h"

#include "phedra/errors.h"

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

bool IntervalCheckReport::passed() const {
  return planarity.value <= tolerance && isometry.value <= tolerance && reproduction <= tolerance &&
         (!closed || closure.value <= tolerance);
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
