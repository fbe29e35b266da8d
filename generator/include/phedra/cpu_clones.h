#pragma once
// PHEDRA_CPU_CLONES before a function's definition: GCC and Clang compile it
// twice, for x86-64-v3 (AVX2, FMA) and for the baseline x86-64, and the loader
// picks the one the processor runs (an ifunc). For the bulk loops where the
// compiler's AVX2 code is measurably faster (docs/performance.md); nothing on
// other targets (WebAssembly, other processors). The two clones may round
// differently (FMA): each is as accurate as the other. GCC 12 and Clang 18 are
// the first to dispatch "arch=" clones (GCC PR101696, LLVM issue 55830): older
// compilers (Debian's clang 14, the sanitizer build's) get the baseline only.
#if defined(__x86_64__) && !defined(__EMSCRIPTEN__) && \
    ((defined(__clang__) && __clang_major__ >= 18) || (!defined(__clang__) && defined(__GNUC__) && __GNUC__ >= 12))
#define PHEDRA_CPU_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
// The same with an x86-64-v4 (AVX-512) clone first: for loops whose 256-bit
// arithmetic gains from its 32 vector registers and broadcasting operands.
#define PHEDRA_CPU_CLONES_V4 __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define PHEDRA_CPU_CLONES
#define PHEDRA_CPU_CLONES_V4
#endif
