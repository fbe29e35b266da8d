#include "phedra/assembly_check.h"

#include "phedra/tube.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <tuple>

namespace phedra {
namespace {

class AssemblyChecker {
 public:
  AssemblyChecker(const Assembly& a, double relative, bool shape = true) : a_(a), shape_(shape) {
    r_.shape_checked = shape;
    r_.name = a.name();
    r_.members = a.member_count();
    r_.shared_groups = a.shared_vertices().size();
    r_.model_size = a.model_size();
    r_.tolerance = relative * a.model_size();
    r_.t_lambda = a.flexion_interval().lower.t;
    r_.t_mu = a.flexion_interval().upper.t;
    r_.t_star = a.t_star();
    r_.member_closure.assign(a.member_count(), 0.0);
    r_.warning = tube_symmetry_warning(a.base().input());
    for (std::size_t m = 0; m < a.member_count(); ++m) {
      r_.closed = r_.closed || a.closed(m);
      figures_.push_back(std::make_unique<FigureTracker>(a.topology(m), a.reference(m), prefix(m)));
    }
    // Every shared vertex against the first of its group, as one flat list in
    // memory order (the groups themselves are scattered on the heap).
    for (const auto& group : a.shared_vertices()) {
      for (std::size_t k = 1; k < group.size(); ++k) shared_pairs_.push_back({group.front(), group[k]});
    }
    std::sort(shared_pairs_.begin(), shared_pairs_.end(), [](const auto& x, const auto& y) {
      return std::tie(x.first.member, x.first.vertex) < std::tie(y.first.member, y.first.vertex);
    });
  }

  void sample(double t) {
    a_.evaluate(t, configuration_);
    for (std::size_t m = 0; m < a_.member_count(); ++m) {
      if (shape_) figures_[m]->observe(t, configuration_.members[m]);
      if (a_.closed(m)) {
        const ClosureGap& gap = configuration_.closure[m];
        if (!(gap.value <= r_.closure.value)) r_.closure.update(gap.value, t, prefix(m) + "row " + std::to_string(gap.row));
        r_.member_closure[m] = std::max(r_.member_closure[m], gap.value);
      }
    }
    member_data_.resize(configuration_.members.size());
    for (std::size_t m = 0; m < member_data_.size(); ++m) member_data_[m] = configuration_.members[m].data();
    for (const auto& [first, other] : shared_pairs_) {
      const double d2 = (member_data_[other.member][other.vertex] - member_data_[first.member][first.vertex]).squaredNorm();
      if (!(d2 <= shared_squared_) && !std::isnan(shared_squared_)) {  // NaN, once found, stays
        shared_squared_ = d2;
        const double d = std::sqrt(d2);
        r_.shared.update(d, t, prefix(first.member) + "vertex " + label(first) + " and " + prefix(other.member) +
                                   "vertex " + label(other));
      }
    }
    ++r_.samples;
  }

  /// Samples t* and compares every member with its constructed net.
  void sample_t_star() {
    sample(a_.t_star());
    for (std::size_t m = 0; m < a_.member_count(); ++m) {
      for (std::size_t v = 0; v < configuration_.members[m].size(); ++v) {
        const double d = (configuration_.members[m][v] - a_.reference(m)[v]).norm();
        if (!(d <= r_.reproduction)) r_.reproduction = d;
      }
    }
  }

  AssemblyCheckReport report() {
    for (const auto& f : figures_) {
      r_.planarity.update(f->planarity().value, f->planarity().t, f->planarity().location);
      r_.isometry.update(f->isometry().value, f->isometry().t, f->isometry().location);
    }
    return r_;
  }

 private:
  std::string prefix(std::size_t m) const {
    return a_.member_count() == 1 ? std::string() : "member " + std::to_string(m) + " (" + a_.member_name(m) + "), ";
  }
  std::string label(const VertexRef& r) const {
    const GridTopology& g = a_.topology(r.member);
    return "(" + std::to_string(g.row_of(r.vertex)) + "," + std::to_string(g.column_of(r.vertex)) + ")";
  }

  const Assembly& a_;
  bool shape_ = true;
  std::vector<std::pair<VertexRef, VertexRef>> shared_pairs_;
  std::vector<const Vec3*> member_data_;  ///< configuration_.members[m].data()
  double shared_squared_ = 0.0;           ///< r_.shared.value squared (NaN: reported already)
  AssemblyConfiguration configuration_;
  std::vector<std::unique_ptr<FigureTracker>> figures_;
  AssemblyCheckReport r_;
};

}  // namespace

bool AssemblyCheckReport::passed() const { return IntervalCheckReport::passed() && shared.value <= tolerance; }

AssemblyCheckReport check_assembly(const Assembly& a, const CheckOptions& options) {
  AssemblyChecker checker(a, options.relative_tolerance, options.shape);
  for (double t : interval_samples(a.flexion_interval().lower.t, a.flexion_interval().upper.t, options.samples)) {
    checker.sample(t);
  }
  checker.sample_t_star();
  return checker.report();
}

AssemblyCheckReport check_assembly_at_t_star(const Assembly& a, double relative) {
  AssemblyChecker checker(a, relative);
  checker.sample_t_star();
  return checker.report();
}

}  // namespace phedra
