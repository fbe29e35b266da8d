#pragma once
// atan2 of n pairs, four at a time with glibc's vector atan2 (libmvec) where the
// processor has AVX2 and FMA, one at a time otherwise. Private to the mechanics.
#include <cstddef>

namespace phedra {

void atan2_many(const double* y, const double* x, double* out, std::size_t n);

}  // namespace phedra
