#include "fold_kernel.h"

#include "vector_atan2.h"

namespace phedra {

FoldKernel::FoldKernel(const BarHingeModel& model) {
  const std::size_t n = model.fold_count();
  for (auto* v : {&j_, &k_, &i_, &l_}) v->resize(n);
  length_.resize(n);
  inverse_square_.resize(n);
  for (std::size_t h = 0; h < n; ++h) {
    const Hinge& hinge = model.hinges()[h];
    j_[h] = static_cast<std::uint32_t>(hinge.nodes[0]);
    k_[h] = static_cast<std::uint32_t>(hinge.nodes[1]);
    i_[h] = static_cast<std::uint32_t>(hinge.nodes[2]);
    l_[h] = static_cast<std::uint32_t>(hinge.nodes[3]);
    length_[h] = hinge.length;
    inverse_square_[h] = 1.0 / (hinge.length * hinge.length);
  }
}

void FoldKernel::angles(const Points& p, const Points* v, double* theta, double* rate, double* y, double* x) const {
  const std::size_t n = size();
  // theta = atan2((m x n) . r_kj / |r_kj|, m . n) and (m x n) . r_kj = |r_kj|^2 (m . r_kl);
  // |r_kj| is the hinge's length (the motion keeps it).
  for (std::size_t h = 0; h < n; ++h) {
    const Vec3& xj = p[j_[h]];
    const Vec3& xk = p[k_[h]];
    const Vec3 rkj = xk - xj, rij = p[i_[h]] - xj, rkl = xk - p[l_[h]];
    const Vec3 m = rij.cross(rkj), nn = rkj.cross(rkl);
    y[h] = length_[h] * m.dot(rkl);
    x[h] = m.dot(nn);
    if (!v) continue;
    // Liu and Paulino's gradient, dotted with the rates (hinge_angle_gradient):
    // d theta / dt = di . (v_i + (a - 1) v_j - a v_k) + dl . (v_l - b v_j + (b - 1) v_k).
    const double a = rij.dot(rkj) * inverse_square_[h], b = rkl.dot(rkj) * inverse_square_[h];
    const Vec3& vj = (*v)[j_[h]];
    const Vec3& vk = (*v)[k_[h]];
    rate[h] = length_[h] * (m.dot((*v)[i_[h]] + (a - 1.0) * vj - a * vk) / m.squaredNorm() -
                            nn.dot((*v)[l_[h]] - b * vj + (b - 1.0) * vk) / nn.squaredNorm());
  }
  atan2_many(y, x, theta, n);
}

}  // namespace phedra
