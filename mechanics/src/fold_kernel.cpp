#include "fold_kernel.h"

#include "vector_atan2.h"

#include "phedra/cpu_clones.h"
#include "phedra/errors.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <type_traits>

namespace phedra {
namespace {

/// A panel's normal direction from its corners (not unit).
Vec3 panel_normal(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) { return (c - a).cross(d - b); }

}  // namespace

FoldKernel::FoldKernel(const BarHingeModel& model) {
  const Points& x = model.positions();
  for (const ModelPanel& p : model.panels()) {
    const std::vector<std::size_t>& v = p.corners;
    const bool quad = v.size() == 4;  // a quad's diagonals; a triangle's sides from corner 0
    panel_a_.push_back(static_cast<std::uint32_t>(v[0]));
    panel_b_.push_back(static_cast<std::uint32_t>(quad ? v[1] : v[0]));
    panel_c_.push_back(static_cast<std::uint32_t>(quad ? v[2] : v[1]));
    panel_d_.push_back(static_cast<std::uint32_t>(quad ? v[3] : v[2]));
    inverse_normal_.push_back(1.0 / panel_normal(x[panel_a_.back()], x[panel_b_.back()], x[panel_c_.back()],
                                                 x[panel_d_.back()]).norm());
  }
  const std::size_t n = model.fold_count();
  for (std::size_t h = 0; h < n; ++h) {
    const Hinge& hinge = model.hinges()[h];
    j_.push_back(static_cast<std::uint32_t>(hinge.nodes[0]));
    k_.push_back(static_cast<std::uint32_t>(hinge.nodes[1]));
    first_.push_back(static_cast<std::uint32_t>(hinge.panels[0]));   // the panel of wing i
    second_.push_back(static_cast<std::uint32_t>(hinge.panels[1]));  // of wing l
    const HingeNodes nodes = hinge_nodes(hinge, x);
    const Vec3 rkj = nodes.k - nodes.j;
    const Vec3 m = (nodes.i - nodes.j).cross(rkj), nn = rkj.cross(nodes.k - nodes.l);
    auto normal = [&](std::uint32_t p) {
      return panel_normal(x[panel_a_[p]], x[panel_b_[p]], x[panel_c_[p]], x[panel_d_[p]]);
    };
    const double along = m.dot(normal(first_.back())) * nn.dot(normal(second_.back()));
    if (!(along != 0.0)) {
      throw Error(ExitCode::internal, "energy: a fold's wing lies on its hinge, or one of its panels has no area");
    }
    signed_inverse_length_.push_back((along > 0.0 ? 1.0 : -1.0) / hinge.length);
  }
}

namespace {

/// Four doubles, one a sample, in one AVX2 register where there is one (GCC's and
/// Clang's vector extension; read and written with memcpy: unaligned). A
/// sample's numbers go through the same operations, in the same order, as the
/// single-sample kernel's (Lane = double): the same bits.
typedef double Four __attribute__((vector_size(4 * sizeof(double))));
template <std::size_t L>
using Lane = std::conditional_t<L == 1, double, Four>;
static_assert(FoldKernel::lanes == 4);

/// Lane l of `v` to out[l * stride].
template <std::size_t L>
[[gnu::always_inline]] inline void scatter(const Lane<L>& v, double* out, std::size_t stride) {
  if constexpr (L == 1) {
    *out = v;
  } else {
    for (std::size_t l = 0; l < L; ++l) out[l * stride] = v[l];
  }
}

}  // namespace

// Inlined into the callers, so that it is compiled in each of their clones (x86-64-v3 and the baseline).
template <std::size_t L>
[[gnu::always_inline]] inline void FoldKernel::panel_frames(const double* p, const double* v, double* f) const {
  // Each panel's unit normal and (with rates) its angular velocity across the normal: 6 numbers a panel (a lane each).
  using T = Lane<L>;
  const std::size_t panels = panel_a_.size();
  for (std::size_t q = 0; q < panels; ++q, f += 6 * L) {
    const double* a = p + 3 * L * panel_a_[q];
    const double* b = p + 3 * L * panel_b_[q];
    const double* c = p + 3 * L * panel_c_[q];
    const double* d = p + 3 * L * panel_d_[q];
    T ax, ay, az, bx, by, bz, cx, cy, cz, dx, dy, dz;
    std::memcpy(&ax, a, sizeof(T)), std::memcpy(&ay, a + L, sizeof(T)), std::memcpy(&az, a + 2 * L, sizeof(T));
    std::memcpy(&bx, b, sizeof(T)), std::memcpy(&by, b + L, sizeof(T)), std::memcpy(&bz, b + 2 * L, sizeof(T));
    std::memcpy(&cx, c, sizeof(T)), std::memcpy(&cy, c + L, sizeof(T)), std::memcpy(&cz, c + 2 * L, sizeof(T));
    std::memcpy(&dx, d, sizeof(T)), std::memcpy(&dy, d + L, sizeof(T)), std::memcpy(&dz, d + 2 * L, sizeof(T));
    const T d1x = cx - ax, d1y = cy - ay, d1z = cz - az, d2x = dx - bx, d2y = dy - by, d2z = dz - bz;
    const double inverse = inverse_normal_[q];  // 1 / |d1 x d2|: the panel is rigid
    const T ux = inverse * (d1y * d2z - d1z * d2y), uy = inverse * (d1z * d2x - d1x * d2z),
            uz = inverse * (d1x * d2y - d1y * d2x);
    std::memcpy(f, &ux, sizeof(T)), std::memcpy(f + L, &uy, sizeof(T)), std::memcpy(f + 2 * L, &uz, sizeof(T));
    if (!v) continue;
    // The panel turns rigidly (the motion is isometric) with some w: its normal's
    // rate is w x unit, so unit x (that rate) is w less its part along the normal,
    // and that part is across every hinge of the panel (they lie in its plane):
    // it adds nothing to a fold's rate. unit x (rate of d1 x d2) / |d1 x d2| is the rest.
    a = v + 3 * L * panel_a_[q], b = v + 3 * L * panel_b_[q], c = v + 3 * L * panel_c_[q], d = v + 3 * L * panel_d_[q];
    std::memcpy(&ax, a, sizeof(T)), std::memcpy(&ay, a + L, sizeof(T)), std::memcpy(&az, a + 2 * L, sizeof(T));
    std::memcpy(&bx, b, sizeof(T)), std::memcpy(&by, b + L, sizeof(T)), std::memcpy(&bz, b + 2 * L, sizeof(T));
    std::memcpy(&cx, c, sizeof(T)), std::memcpy(&cy, c + L, sizeof(T)), std::memcpy(&cz, c + 2 * L, sizeof(T));
    std::memcpy(&dx, d, sizeof(T)), std::memcpy(&dy, d + L, sizeof(T)), std::memcpy(&dz, d + 2 * L, sizeof(T));
    const T e1x = cx - ax, e1y = cy - ay, e1z = cz - az, e2x = dx - bx, e2y = dy - by, e2z = dz - bz;
    // dn = e1 x d2 + d1 x e2 (e: the diagonals' rates)
    const T nx = (e1y * d2z - e1z * d2y) + (d1y * e2z - d1z * e2y);
    const T ny = (e1z * d2x - e1x * d2z) + (d1z * e2x - d1x * e2z);
    const T nz = (e1x * d2y - e1y * d2x) + (d1x * e2y - d1y * e2x);
    const T wx = inverse * (uy * nz - uz * ny), wy = inverse * (uz * nx - ux * nz), wz = inverse * (ux * ny - uy * nx);
    std::memcpy(f + 3 * L, &wx, sizeof(T)), std::memcpy(f + 4 * L, &wy, sizeof(T)), std::memcpy(f + 5 * L, &wz, sizeof(T));
  }
}

template <std::size_t L>
[[gnu::always_inline]] inline void FoldKernel::block(std::size_t h0, std::size_t count, const double* p, bool rates,
                                                     const double* frames, double* theta, double* rate, double* y,
                                                     double* x, std::size_t stride) const {
  using T = Lane<L>;
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t h = h0 + i;
    const double* fa = frames + 6 * L * first_[h];
    const double* fb = frames + 6 * L * second_[h];
    const double* pk = p + 3 * L * k_[h];
    const double* pj = p + 3 * L * j_[h];
    T ax, ay, az, bx, by, bz, kx, ky, kz, jx, jy, jz;
    std::memcpy(&ax, fa, sizeof(T)), std::memcpy(&ay, fa + L, sizeof(T)), std::memcpy(&az, fa + 2 * L, sizeof(T));
    std::memcpy(&bx, fb, sizeof(T)), std::memcpy(&by, fb + L, sizeof(T)), std::memcpy(&bz, fb + 2 * L, sizeof(T));
    std::memcpy(&kx, pk, sizeof(T)), std::memcpy(&ky, pk + L, sizeof(T)), std::memcpy(&kz, pk + 2 * L, sizeof(T));
    std::memcpy(&jx, pj, sizeof(T)), std::memcpy(&jy, pj + L, sizeof(T)), std::memcpy(&jz, pj + 2 * L, sizeof(T));
    // With n_B's sign s and e = r_kj / |r_kj|: y = e . (n_A x s n_B) = (s / |r_kj|) r_kj . (n_A x n_B).
    const double scaled = signed_inverse_length_[h];
    const T rx = kx - jx, ry = ky - jy, rz = kz - jz;
    const T cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
    const T yy = scaled * ((rx * cx + ry * cy) + rz * cz);
    const T xx = std::copysign(1.0, scaled) * ((ax * bx + ay * by) + az * bz);
    scatter<L>(yy, y + i, stride), scatter<L>(xx, x + i, stride);
    if (!rates) continue;
    // d theta / dt: the panels' relative turning rate about the hinge (e runs j to k).
    T wax, way, waz, wbx, wby, wbz;
    std::memcpy(&wax, fa + 3 * L, sizeof(T)), std::memcpy(&way, fa + 4 * L, sizeof(T)), std::memcpy(&waz, fa + 5 * L, sizeof(T));
    std::memcpy(&wbx, fb + 3 * L, sizeof(T)), std::memcpy(&wby, fb + 4 * L, sizeof(T)), std::memcpy(&wbz, fb + 5 * L, sizeof(T));
    const T rr = std::abs(scaled) * ((rx * (wbx - wax) + ry * (wby - way)) + rz * (wbz - waz));
    scatter<L>(rr, rate + i, stride);
  }
  // Every fold through glibc's vector atan2 (four at a time), whatever the block
  // and the lanes: the padding (0, 1) is a zero angle, discarded.
  const std::size_t padded = (count + 3) / 4 * 4;
  for (std::size_t l = 0; l < L; ++l) {
    std::fill(y + l * stride + count, y + l * stride + padded, 0.0);
    std::fill(x + l * stride + count, x + l * stride + padded, 1.0);
    atan2_many(y + l * stride, x + l * stride, theta + l * stride, padded);
  }
}

namespace {
// Four arrays of it and the lanes: 8 KiB a lane, in the first cache levels. A multiple of 4.
constexpr std::size_t block_size = 256;
static_assert(block_size % 4 == 0);
}  // namespace

PHEDRA_CPU_CLONES void FoldKernel::angles(const Points& p, const Points* v, double* theta, double* rate,
                                          std::vector<double>& frames) const {
  frames.resize(6 * panel_a_.size());
  panel_frames<1>(p.data()->data(), v ? v->data()->data() : nullptr, frames.data());
  double y[block_size], x[block_size], out[block_size];
  for (std::size_t h0 = 0; h0 < size(); h0 += block_size) {
    const std::size_t count = std::min(block_size, size() - h0);
    block<1>(h0, count, p.data()->data(), v, frames.data(), out, v ? rate + h0 : nullptr, y, x, block_size);
    std::copy(out, out + count, theta + h0);
  }
}

template <std::size_t L>
[[gnu::always_inline]] inline void FoldKernel::energy(const double* p, const double* v, const double* reference,
                                                      const double* rest, const double* weight, double* const* angles,
                                                      std::int8_t* const* turns, Sums* sums, double* frames) const {
  panel_frames<L>(p, v, frames);
  const double turn = 2.0 * std::numbers::pi, per_turn = 1.0 / turn;
  const double shifter = 0x1.8p52;  // x + shifter - shifter: x rounded to a whole number (|x| < 2^51)
  double y[L * block_size], x[L * block_size], theta[L * block_size], rate[L * block_size];
  // Four partial sums of each, a lane (no chain of additions each waiting for the
  // one before): fold h of a block in partial h % 4, four folds at once; summed at the end.
  constexpr std::size_t partial = 4;
  Four energy_sum[L] = {}, rate_sum[L] = {}, largest[L] = {};
  for (std::size_t h0 = 0; h0 < size(); h0 += block_size) {
    const std::size_t count = std::min(block_size, size() - h0);
    block<L>(h0, count, p, v != nullptr, frames, theta, rate, y, x, block_size);
    if (!v) std::fill(rate, rate + L * block_size, 0.0);
    // Lane by lane: lane l's angles continuous from lane l - 1's (lane 0's from `reference`).
    for (std::size_t l = 0; l < L; ++l) {
      const double* near = l == 0 ? reference : angles[l - 1];
      double* out = angles[l];
      std::int8_t* whole_turns = turns[l];
      const double* raws = theta + l * block_size;
      const double* rates = rate + l * block_size;
      const std::size_t whole_partials = count / partial * partial;
      for (std::size_t i = 0; i < whole_partials; i += partial) {
        const std::size_t h = h0 + i;
        Four raw, w, r, d;
        std::memcpy(&raw, raws + i, sizeof raw);
        Four whole;
        if (near) {
          Four n;
          std::memcpy(&n, near + h, sizeof n);
          whole = ((n - raw) * per_turn + shifter) - shifter;
          for (std::size_t s = 0; s < partial; ++s) whole_turns[h + s] = static_cast<std::int8_t>(whole[s]);
          const Four continuous = raw + turn * whole;
          Four off = continuous - n;
          off = off < 0.0 ? -off : off;
          largest[l] = largest[l] < off ? off : largest[l];
          std::memcpy(out + h, &continuous, sizeof continuous);
          std::memcpy(&d, rest + h, sizeof d);
          d = continuous - d;
        } else {
          for (std::size_t s = 0; s < partial; ++s) whole[s] = whole_turns[h + s];
          const Four continuous = raw + turn * whole;
          std::memcpy(out + h, &continuous, sizeof continuous);
          std::memcpy(&d, rest + h, sizeof d);
          d = continuous - d;
        }
        std::memcpy(&w, weight + h, sizeof w);
        std::memcpy(&r, rates + i, sizeof r);
        const Four wd = w * d;
        energy_sum[l] += wd * d;
        rate_sum[l] += wd * r;
      }
      for (std::size_t i = whole_partials; i < count; ++i) {  // the last block's last folds, one at a time
        const std::size_t h = h0 + i, s = i % partial;
        const double raw = raws[i];
        double whole;
        if (near) {
          whole = ((near[h] - raw) * per_turn + shifter) - shifter;
          whole_turns[h] = static_cast<std::int8_t>(whole);
        } else {
          whole = whole_turns[h];
        }
        const double continuous = raw + turn * whole;
        if (near) largest[l][s] = std::max(largest[l][s], std::abs(continuous - near[h]));
        out[h] = continuous;
        const double d = continuous - rest[h], wd = weight[h] * d;
        energy_sum[l][s] += wd * d;
        rate_sum[l][s] += wd * rates[i];
      }
    }
  }
  for (std::size_t l = 0; l < L; ++l) {
    sums[l].energy = 0.5 * ((energy_sum[l][0] + energy_sum[l][1]) + (energy_sum[l][2] + energy_sum[l][3]));
    sums[l].rate = (rate_sum[l][0] + rate_sum[l][1]) + (rate_sum[l][2] + rate_sum[l][3]);
    sums[l].largest = std::max(std::max(largest[l][0], largest[l][1]), std::max(largest[l][2], largest[l][3]));
  }
}

PHEDRA_CPU_CLONES FoldKernel::Sums FoldKernel::energy(const Points& p, const Points* v, const double* reference,
                                                      const double* rest, const double* weight, double* angles,
                                                      std::int8_t* turns, std::vector<double>& frames) const {
  frames.resize(6 * panel_a_.size());
  Sums out;
  energy<1>(p.data()->data(), v ? v->data()->data() : nullptr, reference, rest, weight, &angles, &turns, &out,
            frames.data());
  return out;
}

PHEDRA_CPU_CLONES void FoldKernel::energy_lanes(const double* p, const double* v, const double* reference,
                                                const double* rest, const double* weight, double* const* angles,
                                                std::int8_t* const* turns, Sums* sums,
                                                std::vector<double>& frames) const {
  frames.resize(6 * lanes * panel_a_.size());
  energy<lanes>(p, v, reference, rest, weight, angles, turns, sums, frames.data());
}

}  // namespace phedra
