#pragma once
// atan2 of n pairs with glibc's vector atan2 (libmvec): eight at a time where the
// processor has AVX-512 (F and DQ), four where it has AVX2 and FMA (the same
// bits: one algorithm), one at a time otherwise. Private to the mechanics.
#include <cstddef>

namespace phedra {

/// The widest vector atan2's count: n a multiple of it runs no narrower call
/// (callers pad their arrays to it).
constexpr std::size_t atan2_group = 8;

void atan2_many(const double* y, const double* x, double* out, std::size_t n);

}  // namespace phedra
