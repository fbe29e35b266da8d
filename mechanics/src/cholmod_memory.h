#pragma once
// CHOLMOD's large blocks on transparent huge pages (internal to mechanics/).
//
// The Cholesky factor of a 10^4-panel array's K is 230 MB, written once and
// read twice a solve: on 4 KiB pages its first touch took 150,000 page faults
// and its reads missed the TLB. Debian's kernels give huge pages to memory
// that asks (transparent_hugepage = madvise), so CHOLMOD's blocks of 2 MiB and
// more are allocated 2 MiB-aligned and advised MADV_HUGEPAGE (docs/performance.md:
// 43,000 page faults instead of 150,000, the modes 3-7 % faster).

namespace phedra {

/// Points SuiteSparse's allocator at one that advises huge pages for large
/// blocks (once; the same malloc/free semantics). Nothing without CHOLMOD.
void cholmod_on_huge_pages();

}  // namespace phedra
