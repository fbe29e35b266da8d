#include "blas_kernels.h"

#include <cstdlib>
#include <cstring>

#if defined(__x86_64__) && defined(__linux__)
#include <unistd.h>

// OpenBLAS's own name of the kernels it chose (weak: null when the BLAS is not OpenBLAS).
extern "C" char* openblas_get_corename(void) __attribute__((weak));
#endif

namespace phedra::cli {

void prefer_blas_kernels_for_this_cpu(char** argv) {
#if defined(__x86_64__) && defined(__linux__)
  // Debian's OpenBLAS (0.3.21) falls back to its Prescott kernels (SSE3) on
  // processors newer than it knows (Intel family 6 model 207, for one), which
  // halves the speed of CHOLMOD's factorization in `phedra mechanics`. When the
  // user has not chosen (OPENBLAS_CORETYPE unset) and the processor has what
  // newer kernels need, choose them and start again: OpenBLAS reads its choice
  // when it is loaded, before main.
  if (openblas_get_corename == nullptr || std::getenv("OPENBLAS_CORETYPE") != nullptr) return;
  const char* core = openblas_get_corename();
  if (core == nullptr || std::strcmp(core, "Prescott") != 0) return;
  __builtin_cpu_init();
  if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma")) return;
  const bool avx512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                      __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq") &&
                      __builtin_cpu_supports("avx512cd");
  if (setenv("OPENBLAS_CORETYPE", avx512 ? "SkylakeX" : "Haswell", 1) != 0) return;
  execv("/proc/self/exe", argv);  // returns only when it fails: go on with the kernels we have
  unsetenv("OPENBLAS_CORETYPE");
#else
  (void)argv;
#endif
}

}  // namespace phedra::cli
