#include "phedra/net_motion.h"

namespace phedra {

NetMotion::NetMotion(const AxialNet& axial, const ParallelNet& parallel, const std::vector<Sign>& signs)
    : rows_(axial.rows),
      columns_(axial.columns),
      ratios_(axial.ratios),
      scales_(parallel.transversal_scales) {
  mirror_.reserve(signs.size());
  for (Sign s : signs) mirror_.push_back(s == Sign::plus ? 1.0 : -1.0);
}

void NetMotion::complete_first_row(double s0, double s1, const Vec3& first, double* s, Vec3* row) const {
  s[0] = s0;
  s[1] = s1;
  row[0] = first;
  for (std::size_t j = 0; j + 1 < columns_; ++j) {
    const double rho = ratios_[j];
    const double c = s[j + 1];
    row[j + 1] = Vec3(rho * row[j].x(), rho * row[j].y(), c + rho * (row[j].z() - c));
    s[j + 2] = row[j + 1].z() + rho * mirror_[j] * (s[j] - row[j].z());
  }
}

}  // namespace phedra
