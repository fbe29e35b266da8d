#include "block_lanczos.h"

#include <algorithm>
#include <cmath>

namespace phedra {
namespace {

/// c = q^T w, then w -= q c, over columns from .. from + count of q (classical
/// Gram-Schmidt of a block), 512 rows at a time: Eigen's GEMM over all the rows
/// packs all of q for each product; by chunks the packed block stays in the
/// caches.
Eigen::MatrixXd orthogonalize(const Eigen::MatrixXd& q, Eigen::Index from, Eigen::Index count, Eigen::MatrixXd& w) {
  constexpr Eigen::Index chunk = 512;
  const Eigen::Index n = w.rows(), b = w.cols();
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(count, b);
  for (Eigen::Index i0 = 0; i0 < n; i0 += chunk) {
    const Eigen::Index len = std::min(chunk, n - i0);
    c.noalias() += q.block(i0, from, len, count).transpose() * w.middleRows(i0, len);
  }
  for (Eigen::Index i0 = 0; i0 < n; i0 += chunk) {
    const Eigen::Index len = std::min(chunk, n - i0);
    w.middleRows(i0, len).noalias() -= q.block(i0, from, len, count) * c;
  }
  return c;
}

}  // namespace

std::optional<Eigen::MatrixXd> block_lanczos_largest(const ApplyFour& apply, const Eigen::MatrixXd& start,
                                                     Eigen::Index nev, double tolerance, Eigen::Index max_basis) {
  constexpr Eigen::Index b = 4;
  const Eigen::Index n = start.rows();
  if (start.cols() != b || max_basis < nev + b || max_basis + b > n) return std::nullopt;
  Eigen::MatrixXd q(n, max_basis + b);  // the basis, a block of four after another
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(max_basis + b, max_basis + b);  // q^T A q
  {
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(start);
    q.leftCols(b) = qr.householderQ() * Eigen::MatrixXd::Identity(n, b);
  }
  Eigen::MatrixXd w(n, b);
  for (Eigen::Index m = 0;; m += b) {  // m: the first column of the newest block
    const Eigen::Index size = m + b;
    apply(q.middleCols(m, b), w);
    const double scale = w.norm();
    // The coefficients are column block m of q^T A q. First against the newest two
    // blocks (in exact arithmetic A q_m lies in their span and the next block's: the
    // three-term recurrence), which takes most of w's norm (60-70 % on the array);
    // then full reorthogonalization against every block (classical Gram-Schmidt,
    // blocked), again while it takes more than 1 - 1/sqrt(2) of a column's norm
    // (Daniel, Gragg, Kaufman and Stewart's criterion: "twice is enough"). On the
    // 10^4-panel array one full pass each step: 45 ms in all, 80 ms with two.
    Eigen::MatrixXd c = Eigen::MatrixXd::Zero(size, b);
    const Eigen::Index recent = std::max<Eigen::Index>(0, m - b);
    c.bottomRows(size - recent) = orthogonalize(q, recent, size - recent, w);
    for (int pass = 0; pass < 3; ++pass) {
      const Eigen::RowVectorXd before = w.colwise().norm();
      c += orthogonalize(q, 0, size, w);
      if ((w.colwise().norm().array() >= std::sqrt(0.5) * before.array()).all()) break;
    }
    h.block(0, m, size, b) = c;
    h.block(m, 0, b, size) = c.transpose();
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(w);
    const Eigen::MatrixXd r = qr.matrixQR().topRows(b).triangularView<Eigen::Upper>();
    // Rayleigh-Ritz: A q_j lies in the span of q and the next block for every block,
    // so A (q y) - theta (q y) = next (r y_newest): the residual is |r y_newest|.
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ritz(
        0.5 * (h.topLeftCorner(size, size) + h.topLeftCorner(size, size).transpose()));
    if (ritz.info() != Eigen::Success) return std::nullopt;
    if (size >= nev) {
      bool converged = true;
      for (Eigen::Index i = 0; i < nev && converged; ++i) {
        const Eigen::Index col = size - 1 - i;  // ascending order: the largest last
        const double theta = ritz.eigenvalues()(col);
        converged = (r * ritz.eigenvectors().col(col).tail(b)).norm() <= tolerance * std::abs(theta);
      }
      if (converged) {
        Eigen::MatrixXd vectors(n, nev);
        for (Eigen::Index i = 0; i < nev; ++i) {
          vectors.col(i) = q.leftCols(size) * ritz.eigenvectors().col(size - 1 - i);
          vectors.col(i).normalize();
        }
        return vectors;
      }
    }
    if (size + b > max_basis) return std::nullopt;
    // A rank-deficient next block: the space is (nearly) invariant; not ours to repair.
    if (r.diagonal().cwiseAbs().minCoeff() <= 1e-12 * scale) return std::nullopt;
    q.middleCols(size, b) = qr.householderQ() * Eigen::MatrixXd::Identity(n, b);
  }
}

}  // namespace phedra
