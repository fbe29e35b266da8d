#include "vector_atan2.h"

#include <cmath>

#if defined(__x86_64__) && !defined(__EMSCRIPTEN__)
#define PHEDRA_VECTOR_ATAN2 1
// The AVX2 half lives in vector_atan2_avx2.cpp, compiled with -mavx2 -mfma as a
// whole, the AVX-512 half in vector_atan2_avx512.cpp likewise: clang (14) passes
// __m256d wrongly to an external function declared with a per-function target
// attribute, so the call must not be made from one.
namespace phedra {
void atan2_avx2(const double* y, const double* x, double* out, std::size_t n);
void atan2_avx512(const double* y, const double* x, double* out, std::size_t n);
}
#endif

namespace phedra {

void atan2_many(const double* y, const double* x, double* out, std::size_t n) {
#ifdef PHEDRA_VECTOR_ATAN2
  static const bool wide = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq");
  static const bool vector = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  if (wide) {
    atan2_avx512(y, x, out, n);
    return;
  }
  if (vector) {
    atan2_avx2(y, x, out, n);
    return;
  }
#endif
  for (std::size_t h = 0; h < n; ++h) out[h] = std::atan2(y[h], x[h]);
}

}  // namespace phedra
