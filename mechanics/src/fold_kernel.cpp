#include "fold_kernel.h"

#include "vector_atan2.h"

#include "phedra/cpu_clones.h"
#include "phedra/errors.h"

#include <algorithm>
#include <bit>
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
/// Four folds' whole turns: as whole numbers, and as the bytes kept (converted
/// four at a time, not one by one).
typedef std::int32_t Whole4 __attribute__((vector_size(4 * sizeof(std::int32_t))));
typedef std::int8_t Turns4 __attribute__((vector_size(4 * sizeof(std::int8_t))));
typedef std::int8_t Bytes16 __attribute__((vector_size(16)));
static_assert(std::endian::native == std::endian::little, "a whole number's low byte first");
static_assert(FoldKernel::lanes == 4);

/// A point's (or vector's) three coordinates, each its L lanes.
template <std::size_t L>
struct Triple {
  Lane<L> x, y, z;
};
/// The triple at p: [coordinate][lane].
template <std::size_t L>
[[gnu::always_inline]] inline void load(const double* p, Triple<L>& out) {
  std::memcpy(&out.x, p, sizeof out.x);
  std::memcpy(&out.y, p + L, sizeof out.y);
  std::memcpy(&out.z, p + 2 * L, sizeof out.z);
}
template <std::size_t L>
[[gnu::always_inline]] inline void store(const Triple<L>& v, double* p) {
  std::memcpy(p, &v.x, sizeof v.x);
  std::memcpy(p + L, &v.y, sizeof v.y);
  std::memcpy(p + 2 * L, &v.z, sizeof v.z);
}

/// A block's numbers made a fold's four lanes side by side ([fold][lane]) to lane
/// l's fold i at out[l * stride + i]: four folds at a time, a 4 x 4 transpose in registers.
[[gnu::always_inline]] inline void transpose_lanes(const double* in, std::size_t count, double* out,
                                                   std::size_t stride) {
  std::size_t i = 0;
  for (; i + 4 <= count; i += 4) {
    Four t0, t1, t2, t3;  // folds i .. i + 3, each its four lanes
    std::memcpy(&t0, in + 4 * i, sizeof t0), std::memcpy(&t1, in + 4 * i + 4, sizeof t1);
    std::memcpy(&t2, in + 4 * i + 8, sizeof t2), std::memcpy(&t3, in + 4 * i + 12, sizeof t3);
    const Four even01 = __builtin_shufflevector(t0, t1, 0, 4, 2, 6), odd01 = __builtin_shufflevector(t0, t1, 1, 5, 3, 7);
    const Four even23 = __builtin_shufflevector(t2, t3, 0, 4, 2, 6), odd23 = __builtin_shufflevector(t2, t3, 1, 5, 3, 7);
    const Four lane0 = __builtin_shufflevector(even01, even23, 0, 1, 4, 5);
    const Four lane1 = __builtin_shufflevector(odd01, odd23, 0, 1, 4, 5);
    const Four lane2 = __builtin_shufflevector(even01, even23, 2, 3, 6, 7);
    const Four lane3 = __builtin_shufflevector(odd01, odd23, 2, 3, 6, 7);
    std::memcpy(out + i, &lane0, sizeof lane0), std::memcpy(out + stride + i, &lane1, sizeof lane1);
    std::memcpy(out + 2 * stride + i, &lane2, sizeof lane2), std::memcpy(out + 3 * stride + i, &lane3, sizeof lane3);
  }
  for (; i < count; ++i) {
    for (std::size_t l = 0; l < 4; ++l) out[l * stride + i] = in[4 * i + l];
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
    Triple<L> a, b, c, d;
    load<L>(p + 3 * L * panel_a_[q], a), load<L>(p + 3 * L * panel_b_[q], b);
    load<L>(p + 3 * L * panel_c_[q], c), load<L>(p + 3 * L * panel_d_[q], d);
    const T d1x = c.x - a.x, d1y = c.y - a.y, d1z = c.z - a.z, d2x = d.x - b.x, d2y = d.y - b.y, d2z = d.z - b.z;
    const double inverse = inverse_normal_[q];  // 1 / |d1 x d2|: the panel is rigid
    const Triple<L> u{inverse * (d1y * d2z - d1z * d2y), inverse * (d1z * d2x - d1x * d2z),
                      inverse * (d1x * d2y - d1y * d2x)};
    store<L>(u, f);
    if (!v) continue;
    // The panel turns rigidly (the motion is isometric) with some w: its normal's
    // rate is w x unit, so unit x (that rate) is w less its part along the normal,
    // and that part is across every hinge of the panel (they lie in its plane):
    // it adds nothing to a fold's rate. unit x (rate of d1 x d2) / |d1 x d2| is the rest.
    load<L>(v + 3 * L * panel_a_[q], a), load<L>(v + 3 * L * panel_b_[q], b);
    load<L>(v + 3 * L * panel_c_[q], c), load<L>(v + 3 * L * panel_d_[q], d);
    const T e1x = c.x - a.x, e1y = c.y - a.y, e1z = c.z - a.z, e2x = d.x - b.x, e2y = d.y - b.y, e2z = d.z - b.z;
    // dn = e1 x d2 + d1 x e2 (e: the diagonals' rates)
    const T nx = (e1y * d2z - e1z * d2y) + (d1y * e2z - d1z * e2y);
    const T ny = (e1z * d2x - e1x * d2z) + (d1z * e2x - d1x * e2z);
    const T nz = (e1x * d2y - e1y * d2x) + (d1x * e2y - d1y * e2x);
    const Triple<L> w{inverse * (u.y * nz - u.z * ny), inverse * (u.z * nx - u.x * nz), inverse * (u.x * ny - u.y * nx)};
    store<L>(w, f + 3 * L);
  }
}

template <std::size_t L>
[[gnu::always_inline]] inline void FoldKernel::block(std::size_t h0, std::size_t count, const double* p, bool rates,
                                                     const double* frames, double* theta, double* rate, double* y,
                                                     double* x, double* turned, std::size_t stride) const {
  // y, x and (with rates, for L > 1) the rates as the kernel makes them, a fold's
  // lanes side by side ([fold][lane]: one vector store a number, no scatter); the
  // atan2 over that array as it is; then theta and the rates lane by lane.
  using T = Lane<L>;
  double* const rate_made = L == 1 ? rate : turned;
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t h = h0 + i;
    const double* fa = frames + 6 * L * first_[h];
    const double* fb = frames + 6 * L * second_[h];
    Triple<L> na, nb, pk, pj;
    load<L>(fa, na), load<L>(fb, nb), load<L>(p + 3 * L * k_[h], pk), load<L>(p + 3 * L * j_[h], pj);
    // With n_B's sign s and e = r_kj / |r_kj|: y = e . (n_A x s n_B) = (s / |r_kj|) r_kj . (n_A x n_B).
    const double scaled = signed_inverse_length_[h];
    const T rx = pk.x - pj.x, ry = pk.y - pj.y, rz = pk.z - pj.z;
    const T cx = na.y * nb.z - na.z * nb.y, cy = na.z * nb.x - na.x * nb.z, cz = na.x * nb.y - na.y * nb.x;
    const T yy = scaled * ((rx * cx + ry * cy) + rz * cz);
    const T xx = std::copysign(1.0, scaled) * ((na.x * nb.x + na.y * nb.y) + na.z * nb.z);
    std::memcpy(y + L * i, &yy, sizeof yy), std::memcpy(x + L * i, &xx, sizeof xx);
    if (!rates) continue;
    // d theta / dt: the panels' relative turning rate about the hinge (e runs j to k).
    Triple<L> wa, wb;
    load<L>(fa + 3 * L, wa), load<L>(fb + 3 * L, wb);
    const T rr = std::abs(scaled) * ((rx * (wb.x - wa.x) + ry * (wb.y - wa.y)) + rz * (wb.z - wa.z));
    std::memcpy(rate_made + L * i, &rr, sizeof rr);
  }
  // Every fold through glibc's vector atan2, whatever the block and the lanes: the
  // padding (0, 1) to a whole number of atan2 groups is a zero angle, discarded.
  const std::size_t made = L * count, padded = (made + atan2_group - 1) / atan2_group * atan2_group;
  std::fill(y + made, y + padded, 0.0);
  std::fill(x + made, x + padded, 1.0);
  if constexpr (L == 1) {
    atan2_many(y, x, theta, padded);
  } else {
    atan2_many(y, x, y, padded);  // in place: each group read before it is written
    transpose_lanes(y, count, theta, stride);
    if (rates) transpose_lanes(turned, count, rate, stride);
  }
}

namespace {
// Five arrays of it and the lanes: 10 KiB a lane, in the first cache levels. A
// multiple of 4 and of the atan2's group.
constexpr std::size_t block_size = 256;
static_assert(block_size % 4 == 0 && block_size % atan2_group == 0);
}  // namespace

PHEDRA_CPU_CLONES void FoldKernel::angles(const Points& p, const Points* v, double* theta, double* rate,
                                          std::vector<double>& frames) const {
  frames.resize(6 * panel_a_.size());
  panel_frames<1>(p.data()->data(), v ? v->data()->data() : nullptr, frames.data());
  double y[block_size], x[block_size], out[block_size];
  for (std::size_t h0 = 0; h0 < size(); h0 += block_size) {
    const std::size_t count = std::min(block_size, size() - h0);
    block<1>(h0, count, p.data()->data(), v, frames.data(), out, v ? rate + h0 : nullptr, y, x, nullptr, block_size);
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
  double turned[L == 1 ? 1 : L * block_size];  // the rates as made, before their transpose
  // Four partial sums of each, a lane (no chain of additions each waiting for the
  // one before): fold h of a block in partial h % 4, four folds at once; summed at the end.
  constexpr std::size_t partial = 4;
  Four energy_sum[L] = {}, rate_sum[L] = {}, largest[L] = {};
  for (std::size_t h0 = 0; h0 < size(); h0 += block_size) {
    const std::size_t count = std::min(block_size, size() - h0);
    block<L>(h0, count, p, v != nullptr, frames, theta, rate, y, x, turned, block_size);
    if (!v) std::fill(rate, rate + L * block_size, 0.0);
    // Lane by lane: lane l's angles continuous from lane l - 1's (lane 0's from `reference`).
    for (std::size_t l = 0; l < L; ++l) {
      const double* near = l == 0 ? reference : angles[l - 1];
      double* out = angles[l];
      std::int8_t* whole_turns = turns[l];
      const double* raws = theta + l * block_size;
      const double* rates = rate + l * block_size;
      // The lane's sums in registers through the block (indexed by l in the arrays they
      // stayed in memory: each fold's update waited for the store of the one before).
      Four energy_l = energy_sum[l], rate_l = rate_sum[l], largest_l = largest[l];
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
          // Each whole number's low byte (the byte of a little-endian int32 at 0, 4, 8, 12): one shuffle.
          const Bytes16 bytes = (Bytes16)__builtin_convertvector(whole, Whole4);
          const Turns4 packed = __builtin_shufflevector(bytes, bytes, 0, 4, 8, 12);
          std::memcpy(whole_turns + h, &packed, sizeof packed);
          const Four continuous = raw + turn * whole;
          Four off = continuous - n;
          off = off < 0.0 ? -off : off;
          largest_l = largest_l < off ? off : largest_l;
          std::memcpy(out + h, &continuous, sizeof continuous);
          std::memcpy(&d, rest + h, sizeof d);
          d = continuous - d;
        } else {
          Turns4 packed;
          std::memcpy(&packed, whole_turns + h, sizeof packed);
          whole = __builtin_convertvector(packed, Four);
          const Four continuous = raw + turn * whole;
          std::memcpy(out + h, &continuous, sizeof continuous);
          std::memcpy(&d, rest + h, sizeof d);
          d = continuous - d;
        }
        std::memcpy(&w, weight + h, sizeof w);
        std::memcpy(&r, rates + i, sizeof r);
        const Four wd = w * d;
        energy_l += wd * d;
        rate_l += wd * r;
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
        if (near) largest_l[s] = std::max(largest_l[s], std::abs(continuous - near[h]));
        out[h] = continuous;
        const double d = continuous - rest[h], wd = weight[h] * d;
        energy_l[s] += wd * d;
        rate_l[s] += wd * rates[i];
      }
      energy_sum[l] = energy_l, rate_sum[l] = rate_l, largest[l] = largest_l;
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
