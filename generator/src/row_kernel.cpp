#include "row_kernel.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(__EMSCRIPTEN__)
#define PHEDRA_ROW_AVX2 1
#include <immintrin.h>
#endif

namespace phedra {

Vec3 advance_row_portable(const RowArguments& r) {
  const double dx = r.first.x() - r.origin.x(), dy = r.first.y() - r.origin.y(), dz = r.first.z() - r.origin.z();
  double* __restrict a = r.axial->data();
  double* __restrict g = r.general->data();
  const double* __restrict p = r.previous->data();
  for (std::size_t j = 0; j < r.count; ++j) {
    const double al = r.alpha[j], b = r.b[j], q = r.q[j];
    const double x = r.origin.x() + al * dx + b * r.axis.x();
    const double y = r.origin.y() + al * dy + b * r.axis.y();
    const double z = r.origin.z() + al * dz + b * r.axis.z();
    g[3 * j] = p[3 * j] + q * (x - a[3 * j]);
    g[3 * j + 1] = p[3 * j + 1] + q * (y - a[3 * j + 1]);
    g[3 * j + 2] = p[3 * j + 2] + q * (z - a[3 * j + 2]);
    a[3 * j] = x;
    a[3 * j + 1] = y;
    a[3 * j + 2] = z;
  }
  return r.count ? r.axial[r.count - 1] : r.first;
}

void advance_uniform_row_portable(const UniformRowArguments& r) {
  const double dx = r.delta.x(), dy = r.delta.y(), dz = r.delta.z();
  double* __restrict g = r.general->data();
  const double* __restrict p = r.previous->data();
  for (std::size_t j = 0; j < r.count; ++j) {
    const double c = r.q[j] * r.alpha[j];
    g[3 * j] = p[3 * j] + c * dx;
    g[3 * j + 1] = p[3 * j + 1] + c * dy;
    g[3 * j + 2] = p[3 * j + 2] + c * dz;
  }
}

#ifdef PHEDRA_ROW_AVX2
namespace {

__attribute__((target("avx2,fma"))) void advance_uniform_row_avx2(const UniformRowArguments& r) {
  const Vec3& d = r.delta;
  const __m256d dp[3] = {_mm256_setr_pd(d.x(), d.y(), d.z(), d.x()), _mm256_setr_pd(d.y(), d.z(), d.x(), d.y()),
                         _mm256_setr_pd(d.z(), d.x(), d.y(), d.z())};
  double* g = r.general->data();
  const double* p = r.previous->data();
  std::size_t j = 0;
  for (; j + 4 <= r.count; j += 4) {
    const __m256d c = _mm256_mul_pd(_mm256_loadu_pd(r.q + j), _mm256_loadu_pd(r.alpha + j));
    const __m256d ck[3] = {_mm256_permute4x64_pd(c, 0x40), _mm256_permute4x64_pd(c, 0xA5), _mm256_permute4x64_pd(c, 0xFE)};
    double* gj = g + 3 * j;
    const double* pj = p + 3 * j;
    for (int k = 0; k < 3; ++k) _mm256_storeu_pd(gj + 4 * k, _mm256_fmadd_pd(ck[k], dp[k], _mm256_loadu_pd(pj + 4 * k)));
  }
  for (; j < r.count; ++j) {  // the last 0..3 vertices
    const double c = r.q[j] * r.alpha[j];
    for (int k = 0; k < 3; ++k) g[3 * j + k] = p[3 * j + k] + c * r.delta[k];
  }
}

/// Four vertices at a time as three vectors of the interleaved x y z: the
/// per-vertex numbers (alpha, b, q) spread over them by lane permutes, the
/// per-row vectors (first - origin, origin, axis) as the same three patterns.
__attribute__((target("avx2,fma"))) Vec3 advance_row_avx2(const RowArguments& r) {
  const Vec3 d = r.first - r.origin;
  // Patterns of a vector (x, y, z) over 4 vertices: (x y z x) (y z x y) (z x y z).
  const __m256d dp[3] = {_mm256_setr_pd(d.x(), d.y(), d.z(), d.x()), _mm256_setr_pd(d.y(), d.z(), d.x(), d.y()),
                         _mm256_setr_pd(d.z(), d.x(), d.y(), d.z())};
  const Vec3& o = r.origin;
  const __m256d op[3] = {_mm256_setr_pd(o.x(), o.y(), o.z(), o.x()), _mm256_setr_pd(o.y(), o.z(), o.x(), o.y()),
                         _mm256_setr_pd(o.z(), o.x(), o.y(), o.z())};
  const Vec3& u = r.axis;
  const __m256d ap[3] = {_mm256_setr_pd(u.x(), u.y(), u.z(), u.x()), _mm256_setr_pd(u.y(), u.z(), u.x(), u.y()),
                         _mm256_setr_pd(u.z(), u.x(), u.y(), u.z())};
  double* a = r.axial->data();
  double* g = r.general->data();
  const double* p = r.previous->data();
  std::size_t j = 0;
  for (; j + 4 <= r.count; j += 4) {
    const __m256d al = _mm256_loadu_pd(r.alpha + j), bb = _mm256_loadu_pd(r.b + j), qq = _mm256_loadu_pd(r.q + j);
    // (v0 v0 v0 v1) (v1 v1 v2 v2) (v2 v3 v3 v3)
    const __m256d alk[3] = {_mm256_permute4x64_pd(al, 0x40), _mm256_permute4x64_pd(al, 0xA5), _mm256_permute4x64_pd(al, 0xFE)};
    const __m256d bk[3] = {_mm256_permute4x64_pd(bb, 0x40), _mm256_permute4x64_pd(bb, 0xA5), _mm256_permute4x64_pd(bb, 0xFE)};
    const __m256d qk[3] = {_mm256_permute4x64_pd(qq, 0x40), _mm256_permute4x64_pd(qq, 0xA5), _mm256_permute4x64_pd(qq, 0xFE)};
    double* aj = a + 3 * j;
    double* gj = g + 3 * j;
    const double* pj = p + 3 * j;
    for (int k = 0; k < 3; ++k) {
      const __m256d axial = _mm256_fmadd_pd(bk[k], ap[k], _mm256_fmadd_pd(alk[k], dp[k], op[k]));
      const __m256d old = _mm256_loadu_pd(aj + 4 * k);
      _mm256_storeu_pd(gj + 4 * k, _mm256_fmadd_pd(qk[k], _mm256_sub_pd(axial, old), _mm256_loadu_pd(pj + 4 * k)));
      _mm256_storeu_pd(aj + 4 * k, axial);
    }
  }
  if (j < r.count) {
    RowArguments rest = r;
    rest.alpha += j;
    rest.b += j;
    rest.q += j;
    rest.count -= j;
    rest.previous += j;
    rest.general += j;
    rest.axial += j;
    advance_row_portable(rest);
  }
  return r.count ? r.axial[r.count - 1] : r.first;
}

bool has_avx2() {
  static const bool yes = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return yes;
}

}  // namespace
#endif

void advance_uniform_row(const UniformRowArguments& r) {
#ifdef PHEDRA_ROW_AVX2
  if (has_avx2()) return advance_uniform_row_avx2(r);
#endif
  advance_uniform_row_portable(r);
}

Vec3 advance_row(const RowArguments& r) {
#ifdef PHEDRA_ROW_AVX2
  if (has_avx2()) return advance_row_avx2(r);
#endif
  return advance_row_portable(r);
}

}  // namespace phedra
