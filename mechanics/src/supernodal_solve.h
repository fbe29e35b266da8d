#pragma once
// The two triangular solves with a supernodal Cholesky factor (internal to mechanics/).
//
// CHOLMOD's own solve calls BLAS's dtrsv and dgemv once a supernode: on the
// 10^4-panel array's factor (2,348 supernodes, 306 MB) 31-33 ms a solve. These
// loops read each entry of the factor once a pass, four columns at a time
// (register-blocked), compiled for AVX2 and the baseline (PHEDRA_CPU_CLONES):
// 27-29 ms, near this machine's streaming bandwidth (docs/performance.md). The
// solve of four has an AVX-512 clone too (the same 256-bit arithmetic with 32
// registers and broadcast operands) and takes the factor eight columns at a time
// with software prefetch: a row of four right-hand sides is read and written once
// for eight of the factor's entries, where the pass had been bound by those loads
// and stores, not by memory: 27.6-29.8 ms against 32.7-36.4 with four columns.

namespace phedra {

/// A supernodal lower-triangular factor L in CHOLMOD's layout (cholmod_factor
/// with is_super): supernode s holds columns super[s] .. super[s+1]-1, its row
/// indices rows[row_start[s] ..] (its own columns first), its values column-
/// major from values + value_start[s], leading dimension its row count.
struct SupernodalFactor {
  int supernodes = 0;
  const int* super = nullptr;
  const int* row_start = nullptr;
  const int* value_start = nullptr;
  const int* rows = nullptr;
  const double* values = nullptr;
};

/// x = (L L^T)^-1 x in L's (permuted) order; work holds as many doubles as L has rows.
void supernodal_solve(const SupernodalFactor& l, double* x, double* work);

/// The same for four right-hand sides at once, interleaved: x[4 i + r] is row i of
/// the r-th. Each entry of L is read once a pass for all four (a solve of four
/// costs about what one does). work holds four doubles a row of L.
void supernodal_solve4(const SupernodalFactor& l, double* x, double* work);

}  // namespace phedra
