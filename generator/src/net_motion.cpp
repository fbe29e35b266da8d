#include "phedra/net_motion.h"

#include <algorithm>

namespace phedra {

NetMotion::NetMotion(const AxialNet& axial, const ParallelNet& parallel, const std::vector<Sign>& signs)
    : rows_(axial.rows),
      columns_(axial.columns),
      ratios_(axial.ratios),
      ratio_stride_(axial.columns - 1),
      scales_(parallel.transversal_scales) {
  mirror_.reserve(signs.size());
  for (Sign s : signs) mirror_.push_back(s == Sign::plus ? 1.0 : -1.0);
  compute_alphas();
}

void NetMotion::compute_alphas() {
  const std::size_t lines = ratio_stride_ == 0 ? 1 : rows_;
  alphas_.assign(lines * columns_, 1.0);
  for (std::size_t i = 0; i < lines; ++i) {
    const double* rho = &ratios_[i * ratio_stride_];
    double* alpha = &alphas_[i * columns_];
    for (std::size_t j = 0; j + 1 < columns_; ++j) alpha[j + 1] = alpha[j] * rho[j];
  }
}

NetMotion::NetMotion(const CanonicalInput& in, const AxialColumn& column, const Points& trajectory,
                     const RowSink& sink)
    : rows_(column.vertices.size()), columns_(in.heights.size() - 1) {
  const std::size_t n = columns_;
  const bool uniform = std::find(in.signs.begin(), in.signs.end(), Sign::minus) == in.signs.end();
  ratio_stride_ = uniform ? 0 : n - 1;
  ratios_.assign((uniform ? 1 : rows_) * (n - 1), 0.0);
  scales_.assign(rows_ * n, 1.0);
  for (Sign s : in.signs) mirror_.push_back(s == Sign::plus ? 1.0 : -1.0);
  Points previous_axial(n), axial(n), previous_general(n), general(n);
  for (std::size_t i = 0; i < rows_; ++i) {
    std::swap(previous_axial, axial);
    std::swap(previous_general, general);
    axial[0] = column.vertices[i];
    build_axial_row(in, i, axial.data(), &ratios_[i * ratio_stride_]);
    build_parallel_row(i, n, previous_axial.data(), axial.data(), previous_general.data(), trajectory[i],
                       column.edge_scale[i], general.data(), &scales_[i * n]);
    sink(i, axial.data(), general.data());
  }
  compute_alphas();
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
