#pragma once
// The singular values and right singular vectors of a dense matrix, by LAPACK's
// dgesdd (Debian's liblapack-dev, served by OpenBLAS): Eigen's BDCSVD does the
// same at twice the time and costs half a minute to compile.
#include <Eigen/Core>

namespace phedra {

/// The singular value decomposition's values and right vectors.
struct RightSingular {
  Eigen::VectorXd values;   ///< descending, min(rows, columns) of them
  Eigen::MatrixXd vectors;  ///< columns x columns, orthonormal: V (its first columns match `values`)
};

/// A = U S V^T of `a`, V complete (the null space's basis too). Throws
/// std::runtime_error when LAPACK fails to converge.
RightSingular right_singular(const Eigen::MatrixXd& a);

}  // namespace phedra
