// Compiled with -mavx2 -mfma (mechanics/CMakeLists.txt), called only when the
// processor has both (vector_atan2.cpp). Nothing inline from a shared header:
// an AVX2 copy of one could be chosen for the whole program.
#if defined(__x86_64__) && !defined(__EMSCRIPTEN__)
#include <immintrin.h>
#include <math.h>
#include <stddef.h>

// glibc's vector atan2 (libmvec, GLIBC_2.35): four doubles, AVX2; within 4 ulp.
extern "C" __m256d _ZGVdN4vv_atan2(__m256d y, __m256d x);

namespace phedra {

void atan2_avx2(const double* y, const double* x, double* out, size_t n) {
  size_t h = 0;
  for (; h + 4 <= n; h += 4) _mm256_storeu_pd(out + h, _ZGVdN4vv_atan2(_mm256_loadu_pd(y + h), _mm256_loadu_pd(x + h)));
  for (; h < n; ++h) out[h] = ::atan2(y[h], x[h]);
}

}  // namespace phedra
#endif
