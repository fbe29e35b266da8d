#include "phedra/hinge_angle.h"

#include <cmath>
#include <numbers>

namespace phedra {
namespace {

struct Frame {
  Vec3 rkj, rij, rkl, m, n;
  double m2, n2, rkj2, rkj_norm;
  explicit Frame(const HingeNodes& x)
      : rkj(x.k - x.j), rij(x.i - x.j), rkl(x.k - x.l), m(rij.cross(rkj)), n(rkj.cross(rkl)) {
    m2 = m.squaredNorm();
    n2 = n.squaredNorm();
    rkj2 = rkj.squaredNorm();
    rkj_norm = std::sqrt(rkj2);
  }
};

}  // namespace

double hinge_angle(const HingeNodes& x) {
  const Frame f(x);
  const double theta = std::atan2(f.m.cross(f.n).dot(f.rkj) / f.rkj_norm, f.m.dot(f.n));
  return theta < 0.0 ? theta + 2.0 * std::numbers::pi : theta;
}

std::array<Vec3, 4> hinge_angle_gradient(const HingeNodes& x) {
  const Frame f(x);
  const Vec3 di = f.m * (f.rkj_norm / f.m2);
  const Vec3 dl = -f.n * (f.rkj_norm / f.n2);
  const double a = f.rij.dot(f.rkj) / f.rkj2, b = f.rkl.dot(f.rkj) / f.rkj2;
  const Vec3 dj = (a - 1.0) * di - b * dl;
  const Vec3 dk = -a * di + (b - 1.0) * dl;
  return {dj, dk, di, dl};
}

Eigen::Matrix<double, 12, 12> hinge_angle_hessian(const HingeNodes& x) {
  // Liu and Paulino (2017), as MERLIN2's GlobalK_fast_ver assembles it.
  const Frame f(x);
  const Vec3 di = f.m * (f.rkj_norm / f.m2);
  const Vec3 dl = -f.n * (f.rkj_norm / f.n2);
  const double a = f.rij.dot(f.rkj) / f.rkj2, b = f.rkl.dot(f.rkj) / f.rkj2;
  auto sym = [](const Vec3& p, const Vec3& q) -> Mat3 { return p * q.transpose() + q * p.transpose(); };
  const double m4 = f.m2 * f.m2, n4 = f.n2 * f.n2;
  const Mat3 dii = -sym(f.m, f.rkj.cross(f.m)) * (f.rkj_norm / m4);
  const Mat3 dij = -(f.m * f.rkj.transpose()) / (f.m2 * f.rkj_norm) +
                   sym(f.m, (f.rkj - f.rij).cross(f.m)) * (f.rkj_norm / m4);
  const Mat3 dik = (f.m * f.rkj.transpose()) / (f.m2 * f.rkj_norm) + sym(f.m, f.rij.cross(f.m)) * (f.rkj_norm / m4);
  const Mat3 dll = sym(f.n, f.rkj.cross(f.n)) * (f.rkj_norm / n4);
  const Mat3 dlk = -(f.n * f.rkj.transpose()) / (f.n2 * f.rkj_norm) -
                   sym(f.n, (f.rkj - f.rkl).cross(f.n)) * (f.rkj_norm / n4);
  const Mat3 dlj = (f.n * f.rkj.transpose()) / (f.n2 * f.rkj_norm) - sym(f.n, f.rkl.cross(f.n)) * (f.rkj_norm / n4);
  const Vec3 t1jj = (f.rkj * (-1.0 + 2.0 * a) - f.rij) / f.rkj2;
  const Vec3 t2jj = (f.rkj * (2.0 * b) - f.rkl) / f.rkj2;
  const Mat3 djj = di * t1jj.transpose() + dij * (a - 1.0) - dl * t2jj.transpose() - dlj * b;
  const Vec3 t1jk = (f.rkj * (-2.0 * a) + f.rij) / f.rkj2;
  const Vec3 t2jk = (f.rkj * (1.0 - 2.0 * b) + f.rkl) / f.rkj2;
  const Mat3 djk = di * t1jk.transpose() + dik * (a - 1.0) - dl * t2jk.transpose() - dlk * b;
  const Mat3 dkk = dl * t2jk.transpose() + dlk * (b - 1.0) - di * t1jk.transpose() - dik * a;

  Eigen::Matrix<double, 12, 12> h = Eigen::Matrix<double, 12, 12>::Zero();
  // Blocks: 0 = j, 1 = k, 2 = i, 3 = l.
  auto put = [&](int r, int c, const Mat3& block) {
    h.block<3, 3>(3 * r, 3 * c) = block;
    if (r != c) h.block<3, 3>(3 * c, 3 * r) = block.transpose();
  };
  put(0, 0, djj);
  put(1, 1, dkk);
  put(2, 2, dii);
  put(3, 3, dll);
  put(0, 1, djk);
  put(2, 0, dij);
  put(3, 0, dlj);
  put(2, 1, dik);
  put(3, 1, dlk);
  return h;
}

double continuous_angle(double theta, double near) {
  const double turn = 2.0 * std::numbers::pi;
  return theta + turn * std::round((near - theta) / turn);
}

}  // namespace phedra
