#pragma once
// The angle of a rotational spring (a fold or bending hinge) of the bar-and-hinge
// model, as MERLIN2 defines it (Liu and Paulino 2017), with its analytic gradient
// and Hessian. A hinge is four nodes [j k i l]: the axis j-k, the wing i of the
// first panel, the wing l of the second. With r_kj = x_k - x_j, r_ij = x_i - x_j,
// r_kl = x_k - x_l, m = r_ij x r_kj and n = r_kj x r_kl:
//
//   theta = atan2((m x n) . r_kj / |r_kj|, m . n)  in [0, 2 pi), pi flat,
//
// the same angle as MERLIN2's sign(n . r_ij) acos(m . n / |m| |n|), without
// acos's ill-conditioning at flat hinges.

#include "phedra/vector_types.h"

#include <Eigen/Core>

#include <array>

namespace phedra {

/// The nodes' positions of one hinge, in the order [j k i l].
struct HingeNodes {
  Vec3 j, k, i, l;
};

/// theta in [0, 2 pi).
double hinge_angle(const HingeNodes& x);

/// d theta / d x for x_j, x_k, x_i, x_l (in that order).
std::array<Vec3, 4> hinge_angle_gradient(const HingeNodes& x);

/// The 12 x 12 Hessian of theta, rows and columns in the order j, k, i, l (x, y, z each).
Eigen::Matrix<double, 12, 12> hinge_angle_hessian(const HingeNodes& x);

/// theta + 2 pi k closest to `near`: an angle kept continuous along a motion
/// (folds reach 0 or 2 pi at a flexion limit, and pass beyond in designs whose
/// panels cross).
double continuous_angle(double theta, double near);

}  // namespace phedra
