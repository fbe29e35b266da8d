#pragma once
// The fold angles and their rates in bulk, for the energy landscape (internal to
// mechanics/): the folds' nodes and lengths as plain arrays, the angles' atan2
// four at a time (glibc's libmvec, AVX2) where the processor has it.

#include "phedra/bar_hinge_model.h"

#include <cstdint>
#include <vector>

namespace phedra {

class FoldKernel {
 public:
  explicit FoldKernel(const BarHingeModel& model);
  std::size_t size() const { return j_.size(); }

  /// theta of every fold at the nodes' positions x, in (-pi, pi] (hinge_angle's
  /// value up to 2 pi), and (rate not null) d theta / dt for the nodes' rates v.
  /// `y`, `x` are scratch of size() entries.
  void angles(const Points& positions, const Points* v, double* theta, double* rate, double* y, double* x) const;

 private:
  std::vector<std::uint32_t> j_, k_, i_, l_;
  std::vector<double> length_, inverse_square_;  ///< |r_kj| (the motion keeps it) and its inverse square
};

}  // namespace phedra
