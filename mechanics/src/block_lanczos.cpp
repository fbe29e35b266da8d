#include "block_lanczos.h"

#include "phedra/cpu_clones.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace phedra {
namespace {

// Four doubles (GCC's and Clang's vector extension), as in supernodal_solve.cpp;
// the helpers are always inlined: no vector crosses a call (-Wpsabi).
#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif
typedef double Lane4 __attribute__((vector_size(32)));
[[gnu::always_inline]] inline Lane4 load4(const double* p) {
  Lane4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
[[gnu::always_inline]] inline void store4(double* p, Lane4 v) { std::memcpy(p, &v, sizeof v); }
[[gnu::always_inline]] inline double sum4(Lane4 v) { return (v[0] + v[1]) + (v[2] + v[3]); }

/// c (count x 4, column-major) += q's columns' dot products with w's four columns
/// over rows [0, len) (q's columns ld apart, w's n apart); len a multiple of four.
/// Two of q's columns at a time: eight independent sums.
[[gnu::always_inline]] inline void add_dots(const double* q, std::size_t ld, Eigen::Index count, const double* w,
                                            std::size_t n, Eigen::Index len, double* c) {
  const double *w0 = w, *w1 = w + n, *w2 = w + 2 * n, *w3 = w + 3 * n;
  Eigen::Index j = 0;
  for (; j + 2 <= count; j += 2) {
    const double *a = q + static_cast<std::size_t>(j) * ld, *b = a + ld;
    Lane4 a0{}, a1{}, a2{}, a3{}, b0{}, b1{}, b2{}, b3{};
    for (Eigen::Index i = 0; i < len; i += 4) {
      const Lane4 x = load4(a + i), y = load4(b + i), v0 = load4(w0 + i), v1 = load4(w1 + i), v2 = load4(w2 + i),
                  v3 = load4(w3 + i);
      a0 += x * v0;
      a1 += x * v1;
      a2 += x * v2;
      a3 += x * v3;
      b0 += y * v0;
      b1 += y * v1;
      b2 += y * v2;
      b3 += y * v3;
    }
    c[j] += sum4(a0), c[count + j] += sum4(a1), c[2 * count + j] += sum4(a2), c[3 * count + j] += sum4(a3);
    c[j + 1] += sum4(b0), c[count + j + 1] += sum4(b1), c[2 * count + j + 1] += sum4(b2), c[3 * count + j + 1] += sum4(b3);
  }
  for (; j < count; ++j) {
    const double* a = q + static_cast<std::size_t>(j) * ld;
    Lane4 a0{}, a1{}, a2{}, a3{};
    for (Eigen::Index i = 0; i < len; i += 4) {
      const Lane4 x = load4(a + i);
      a0 += x * load4(w0 + i);
      a1 += x * load4(w1 + i);
      a2 += x * load4(w2 + i);
      a3 += x * load4(w3 + i);
    }
    c[j] += sum4(a0), c[count + j] += sum4(a1), c[2 * count + j] += sum4(a2), c[3 * count + j] += sum4(a3);
  }
}

/// w's four columns -= q c over rows [0, len), eight rows at a time (eight
/// independent sums over q's columns); len a multiple of four.
[[gnu::always_inline]] inline void subtract_products(const double* q, std::size_t ld, Eigen::Index count,
                                                     const double* c, double* w, std::size_t n, Eigen::Index len) {
  double *w0 = w, *w1 = w + n, *w2 = w + 2 * n, *w3 = w + 3 * n;
  Eigen::Index i = 0;
  for (; i + 8 <= len; i += 8) {
    Lane4 s0{}, s1{}, s2{}, s3{}, t0{}, t1{}, t2{}, t3{};
    for (Eigen::Index j = 0; j < count; ++j) {
      const double* a = q + static_cast<std::size_t>(j) * ld + i;
      const Lane4 x = load4(a), y = load4(a + 4);
      const double c0 = c[j], c1 = c[count + j], c2 = c[2 * count + j], c3 = c[3 * count + j];
      s0 += x * c0;
      s1 += x * c1;
      s2 += x * c2;
      s3 += x * c3;
      t0 += y * c0;
      t1 += y * c1;
      t2 += y * c2;
      t3 += y * c3;
    }
    store4(w0 + i, load4(w0 + i) - s0), store4(w1 + i, load4(w1 + i) - s1);
    store4(w2 + i, load4(w2 + i) - s2), store4(w3 + i, load4(w3 + i) - s3);
    store4(w0 + i + 4, load4(w0 + i + 4) - t0), store4(w1 + i + 4, load4(w1 + i + 4) - t1);
    store4(w2 + i + 4, load4(w2 + i + 4) - t2), store4(w3 + i + 4, load4(w3 + i + 4) - t3);
  }
  for (; i < len; i += 4) {
    Lane4 s0{}, s1{}, s2{}, s3{};
    for (Eigen::Index j = 0; j < count; ++j) {
      const Lane4 x = load4(q + static_cast<std::size_t>(j) * ld + i);
      s0 += x * c[j];
      s1 += x * c[count + j];
      s2 += x * c[2 * count + j];
      s3 += x * c[3 * count + j];
    }
    store4(w0 + i, load4(w0 + i) - s0), store4(w1 + i, load4(w1 + i) - s1);
    store4(w2 + i, load4(w2 + i) - s2), store4(w3 + i, load4(w3 + i) - s3);
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
    add_dots(q + i0, n, count, w + i0, n, std::min(chunk, whole - i0), c);
  }
  for (Eigen::Index i = whole; i < rows; ++i) {  // the last rows, fewer than four
    for (Eigen::Index j = 0; j < count; ++j) {
      for (int r = 0; r < 4; ++r) c[r * count + j] += q[static_cast<std::size_t>(j) * n + i] * w[r * n + i];
    }
  }
  for (Eigen::Index i0 = 0; i0 < whole; i0 += chunk) {
    subtract_products(q + i0, n, count, c, w + i0, n, std::min(chunk, whole - i0));
  }
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
