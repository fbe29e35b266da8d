// Compiled with -mavx512f -mavx512dq (mechanics/CMakeLists.txt), called only
// when the processor has both (vector_atan2.cpp). Nothing inline from a shared
// header: an AVX-512 copy of one could be chosen for the whole program.
#if defined(__x86_64__) && !defined(__EMSCRIPTEN__)
#include <immintrin.h>
#include <math.h>
#include <stddef.h>

// glibc's vector atan2 (libmvec, GLIBC_2.35), eight doubles: the same algorithm
// as the four-wide one (the same bits on 2 x 10^7 pairs tested), a quarter faster
// an angle on AMD's Zen 4 (docs/performance.md, session 37).
extern "C" __m512d _ZGVeN8vv_atan2(__m512d y, __m512d x);
extern "C" __m256d _ZGVdN4vv_atan2(__m256d y, __m256d x);

namespace phedra {

void atan2_avx512(const double* y, const double* x, double* out, size_t n) {
  size_t h = 0;
  for (; h + 8 <= n; h += 8) _mm512_storeu_pd(out + h, _ZGVeN8vv_atan2(_mm512_loadu_pd(y + h), _mm512_loadu_pd(x + h)));
  for (; h + 4 <= n; h += 4) _mm256_storeu_pd(out + h, _ZGVdN4vv_atan2(_mm256_loadu_pd(y + h), _mm256_loadu_pd(x + h)));
  for (; h < n; ++h) out[h] = ::atan2(y[h], x[h]);
}

}  // namespace phedra
#endif
