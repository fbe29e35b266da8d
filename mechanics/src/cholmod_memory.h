#pragma once
// CHOLMOD's large blocks on transparent huge pages where they pay (internal to mechanics/).
//
// The Cholesky factor of a 10^4-panel array's K is 300 MB, written once and
// read twice a solve: on 4 KiB pages its first touch took 150,000 page faults
// and its reads missed the TLB. Debian's kernels give huge pages to memory
// that asks (transparent_hugepage = madvise), so CHOLMOD's blocks of 2 MiB and
// more are allocated 2 MiB-aligned and advised MADV_HUGEPAGE (docs/performance.md:
// 43,000 page faults instead of 150,000, the modes 3-7 % faster).
//
// Except in a virtual machine whose guest hands its free memory back to the
// host (virtio-balloon's free page reporting, which reports free blocks of 2 MiB
// and more): a fresh huge page is then one the host has dropped, and its first
// touch costs the host's faults (the array's first analysis 2.2-2.4 s against
// 1.65-1.75 s when the pages were touched a moment before). There the blocks
// stay on 4 KiB pages, which come from memory the guest freed recently, and are
// populated in one call (MADV_POPULATE_WRITE) instead of a fault a page: every
// analysis 1.8-1.86 s. `PHEDRA_HUGE_PAGES=1` or `=0` chooses instead.

#include <filesystem>

namespace phedra {

/// Points SuiteSparse's allocator at one that advises huge pages for large
/// blocks where they pay (once; the same malloc/free semantics). Nothing without CHOLMOD.
void cholmod_on_huge_pages();

/// Whether a virtio balloon under `virtio_devices` (the kernel's
/// /sys/bus/virtio/devices) negotiated free page reporting (feature bit 5).
bool reports_free_pages(const std::filesystem::path& virtio_devices);

}  // namespace phedra
