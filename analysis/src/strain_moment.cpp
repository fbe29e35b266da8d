// The strain's moment from points and their weights (HomogenizedStrain::state_of
// with weights), of one sample or of four side by side (the energy landscape's
// samples evaluated together): the same sums in the same order for each, and
// this file is compiled without FMA contraction (analysis/CMakeLists.txt), so a
// sample's moment has the same bits either way.

#include "phedra/cpu_clones.h"
#include "phedra/homogenized_strain.h"

#include <cstring>
#include <type_traits>

namespace phedra {
namespace {

/// Four doubles, one a sample (GCC's and Clang's vector extension).
typedef double Four __attribute__((vector_size(4 * sizeof(double))));

/// out[l] = sum over the points q of (x_q - anchor) w_q^T, each entry summed in
/// the points' order; x is [point][coordinate][lane], L lanes.
template <std::size_t L>
[[gnu::always_inline]] inline void moments(const double* x, const Vec3& anchor, const Points& weights, Mat3* out) {
  // Named sums, not arrays: GCC kept arrays of them in memory (and a coordinate
  // copied in halves stalled its reload: no store forwarding).
  using T = std::conditional_t<L == 1, double, Four>;
  T m00{}, m01{}, m02{}, m10{}, m11{}, m12{}, m20{}, m21{}, m22{};
  for (std::size_t q = 0; q < weights.size(); ++q, x += 3 * L) {
    T dx, dy, dz;
    std::memcpy(&dx, x, sizeof dx);
    std::memcpy(&dy, x + L, sizeof dy);
    std::memcpy(&dz, x + 2 * L, sizeof dz);
    dx = dx - anchor.x(), dy = dy - anchor.y(), dz = dz - anchor.z();
    const double wx = weights[q].x(), wy = weights[q].y(), wz = weights[q].z();
    m00 += dx * wx, m01 += dx * wy, m02 += dx * wz;
    m10 += dy * wx, m11 += dy * wy, m12 += dy * wz;
    m20 += dz * wx, m21 += dz * wy, m22 += dz * wz;
  }
  const T m[9] = {m00, m01, m02, m10, m11, m12, m20, m21, m22};
  for (std::size_t l = 0; l < L; ++l) {
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        if constexpr (L == 1) {
          out[l](a, b) = m[3 * a + b];
        } else {
          out[l](a, b) = m[3 * a + b][l];
        }
      }
    }
  }
}

}  // namespace

PHEDRA_CPU_CLONES Mat3 HomogenizedStrain::weighted_moment(const Points& x, const Points& weights) const {
  // sum over the vertices of (x - a) Y^T, the vertices at one point summed first (their Y into its weight).
  Mat3 out;
  moments<1>(x.data()->data(), anchor_, weights, &out);
  return out;
}

PHEDRA_CPU_CLONES void HomogenizedStrain::weighted_moments_lanes(const double* x, const Points& weights,
                                                                 Mat3* out) const {
  moments<4>(x, anchor_, weights, out);
}

}  // namespace phedra
