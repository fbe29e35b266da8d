#pragma once
// CHOLMOD's numeric factorization on the calling thread alone (internal to mechanics/).
//
// Debian's CHOLMOD (SuiteSparse 5.12) runs the small loops of its supernodal
// factorization (clearing a supernode, its row map, the scatter of each update)
// as OpenMP regions of a fixed 4 threads (`num_threads(CHOLMOD_OMP_NUM_THREADS)`,
// which OMP_NUM_THREADS does not change), thousands of regions a factorization.
// On a 2-core machine the 4 threads' barriers cost more than the loops: the
// 10^4-panel array's factorization took 1.44-1.59 s with them, 1.03-1.19 s
// with the regions on one thread (and no faster with two: docs/performance.md).
// BLAS, where the work is, stays as it was (Debian's serial OpenBLAS).

namespace phedra {

/// While alive, OpenMP regions that the calling thread starts run on it alone
/// (its max-active-levels set to 0, restored after; libgomp keeps that value
/// a thread, so other threads are untouched). Nothing when no OpenMP runtime is
/// loaded (CHOLMOD built without it, or WebAssembly).
class OpenMPRegionsSerial {
 public:
  OpenMPRegionsSerial();
  ~OpenMPRegionsSerial();
  OpenMPRegionsSerial(const OpenMPRegionsSerial&) = delete;
  OpenMPRegionsSerial& operator=(const OpenMPRegionsSerial&) = delete;

 private:
  int previous_ = -1;  ///< the thread's max-active-levels before; -1: nothing changed
};

}  // namespace phedra
