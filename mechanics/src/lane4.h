#pragma once
// Four doubles (GCC's and Clang's vector extension: one AVX register, or two SSE2
// ones) for the hand-vectorized loops of mechanics/ (internal to mechanics/): the
// solves with the Cholesky factor and the block Lanczos's Gram-Schmidt. The
// helpers are always inlined and take their vectors by reference, and the loops
// that use them have internal linkage: no vector crosses an ABI boundary (GCC's
// note that 32-byte vectors pass differently without AVX, -Wpsabi, which its
// pragma does not silence, is for by-value vector parameters).
#include <cstring>

#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace phedra {

typedef double Lane4 __attribute__((vector_size(32)));

// Always inlined: each CPU clone of a caller gets its own (AVX2 registers in the
// x86-64-v3 one).
[[gnu::always_inline]] inline Lane4 load4(const double* p) {
  Lane4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
[[gnu::always_inline]] inline void store4(double* p, const Lane4& v) { std::memcpy(p, &v, sizeof v); }
[[gnu::always_inline]] inline double sum4(const Lane4& v) { return (v[0] + v[1]) + (v[2] + v[3]); }

}  // namespace phedra
