#include "block_lanczos.h"

#include "lane4.h"
#include "phedra/cpu_clones.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace phedra {
namespace {

/// c (count x 4, column-major) += the dot products of q's columns j .. j + C with
/// w's four columns over rows [0, len) (q's columns ld apart, w's n apart); len a
/// multiple of four. C = 2: eight independent sums.
template <int C>
[[gnu::always_inline]] inline void add_dots(const double* q, std::size_t ld, Eigen::Index j, Eigen::Index count,
                                            const double* w, std::size_t n, Eigen::Index len, double* c) {
  Lane4 sums[C][4] = {};
  for (Eigen::Index i = 0; i < len; i += 4) {
    const Lane4 v[4] = {load4(w + i), load4(w + n + i), load4(w + 2 * n + i), load4(w + 3 * n + i)};
    for (int k = 0; k < C; ++k) {
      const Lane4 x = load4(q + static_cast<std::size_t>(j + k) * ld + i);
      for (int r = 0; r < 4; ++r) sums[k][r] += x * v[r];
    }
  }
  for (int k = 0; k < C; ++k) {
    for (int r = 0; r < 4; ++r) c[r * count + j + k] += sum4(sums[k][r]);
  }
}

/// w's four columns -= q c over rows [i, i + 4 R) (q's columns ld apart, w's n
/// apart). R = 2: eight independent sums over q's columns.
template <int R>
[[gnu::always_inline]] inline void subtract_products(const double* q, std::size_t ld, Eigen::Index count,
                                                     const double* c, double* w, std::size_t n, Eigen::Index i) {
  Lane4 sums[R][4] = {};
  for (Eigen::Index j = 0; j < count; ++j) {
    const double* column = q + static_cast<std::size_t>(j) * ld + i;
    const double cj[4] = {c[j], c[count + j], c[2 * count + j], c[3 * count + j]};
    for (int h = 0; h < R; ++h) {
      const Lane4 x = load4(column + 4 * h);
      for (int r = 0; r < 4; ++r) sums[h][r] += x * cj[r];
    }
  }
  for (int h = 0; h < R; ++h) {
    for (int r = 0; r < 4; ++r) {
      double* target = w + static_cast<std::size_t>(r) * n + i + 4 * h;
      store4(target, load4(target) - sums[h][r]);
    }
  }
}

/// c = q^T w, then w -= q c, over columns from .. from + count of q (classical
/// Gram-Schmidt of a block of four), by chunks of 512 rows (w's chunk stays in the
/// first-level cache while q's columns stream past). Eigen's GEMM packed q's
/// chunk for each product, as much work as the product itself with four columns:
/// on the 10^4-panel array 26-36 ms in all against 42-47 (docs/performance.md).
PHEDRA_CPU_CLONES void orthogonalize_kernel(const double* q, std::size_t n, Eigen::Index count, double* w, double* c) {
  constexpr Eigen::Index chunk = 512;
  const Eigen::Index rows = static_cast<Eigen::Index>(n), whole = rows / 4 * 4;
  for (Eigen::Index i0 = 0; i0 < whole; i0 += chunk) {
    const Eigen::Index len = std::min(chunk, whole - i0);
    Eigen::Index j = 0;
    for (; j + 2 <= count; j += 2) add_dots<2>(q + i0, n, j, count, w + i0, n, len, c);
    if (j < count) add_dots<1>(q + i0, n, j, count, w + i0, n, len, c);
  }
  for (Eigen::Index i = whole; i < rows; ++i) {  // the last rows, fewer than four
    for (Eigen::Index j = 0; j < count; ++j) {
      for (int r = 0; r < 4; ++r) c[r * count + j] += q[static_cast<std::size_t>(j) * n + i] * w[r * n + i];
    }
  }
  Eigen::Index row = 0;
  for (; row + 8 <= whole; row += 8) subtract_products<2>(q, n, count, c, w, n, row);
  if (row < whole) subtract_products<1>(q, n, count, c, w, n, row);
  for (Eigen::Index i = whole; i < rows; ++i) {
    for (int r = 0; r < 4; ++r) {
      double sum = 0.0;
      for (Eigen::Index j = 0; j < count; ++j) sum += q[static_cast<std::size_t>(j) * n + i] * c[r * count + j];
      w[r * n + i] -= sum;
    }
  }
}

Eigen::MatrixXd orthogonalize(const Eigen::MatrixXd& q, Eigen::Index from, Eigen::Index count, Eigen::MatrixXd& w) {
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(count, w.cols());
  orthogonalize_kernel(q.data() + from * q.rows(), static_cast<std::size_t>(q.rows()), count, w.data(), c.data());
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
    // 10^4-panel array one full pass each step: 26-36 ms in all (Eigen's GEMM: 45 ms,
    // 80 ms with two passes).
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
        // One product for all: the basis read once, not once a vector.
        const Eigen::MatrixXd y = ritz.eigenvectors().rightCols(nev).rowwise().reverse();
        Eigen::MatrixXd vectors = q.leftCols(size) * y;
        vectors.colwise().normalize();
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
