#pragma once
// PHEDRA_CPU_CLONES before a function's definition: GCC and Clang compile it
// twice, for x86-64-v3 (AVX2, FMA) and for the baseline x86-64, and the loader
// picks the one the processor runs (an ifunc). For the bulk loops where the
// compiler's AVX2 code is measurably faster (docs/performance.md); nothing on
// other targets (WebAssembly, other processors). The two clones may round
// differently (FMA): each is as accurate as the other.
#if defined(__x86_64__) && !defined(__EMSCRIPTEN__) && (defined(__GNUC__) || defined(__clang__))
#define PHEDRA_CPU_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define PHEDRA_CPU_CLONES
#endif
