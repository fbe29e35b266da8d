#pragma once
// The BLAS kernels for this processor (the command only: it may start itself again).

namespace phedra::cli {

/// When the BLAS is OpenBLAS, nobody chose its kernels (OPENBLAS_CORETYPE unset)
/// and it fell back to its oldest x86-64 ones (Prescott) on a processor with
/// AVX2 and FMA it does not know, starts this program again with the kernels for
/// that processor (SkylakeX with AVX-512, else Haswell). Returns otherwise.
void prefer_blas_kernels_for_this_cpu(char** argv);

}  // namespace phedra::cli
