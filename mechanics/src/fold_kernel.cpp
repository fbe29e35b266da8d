#include "fold_kernel.h"

#include "vector_atan2.h"

#include "phedra/cpu_clones.h"
#include "phedra/errors.h"

#include <algorithm>
#include <cmath>
#include <numbers>

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

PHEDRA_CPU_CLONES void FoldKernel::panel_frames(const Points& p, const Points* v, std::vector<double>& frames) const {
  // Each panel's unit normal and (with rates) its angular velocity across the normal: 6 numbers a panel.
  const std::size_t panels = panel_a_.size();
  frames.resize(6 * panels);
  double* f = frames.data();
  for (std::size_t q = 0; q < panels; ++q, f += 6) {
    const Vec3& a = p[panel_a_[q]];
    const Vec3& b = p[panel_b_[q]];
    const Vec3 d1 = p[panel_c_[q]] - a, d2 = p[panel_d_[q]] - b;
    const double inverse = inverse_normal_[q];  // 1 / |d1 x d2|: the panel is rigid
    const Vec3 unit = inverse * d1.cross(d2);
    f[0] = unit.x();
    f[1] = unit.y();
    f[2] = unit.z();
    if (!v) continue;
    // The panel turns rigidly (the motion is isometric) with some w: its normal's
    // rate is w x unit, so unit x (that rate) is w less its part along the normal,
    // and that part is across every hinge of the panel (they lie in its plane):
    // it adds nothing to a fold's rate. unit x (rate of d1 x d2) / |d1 x d2| is the rest.
    const Vec3 dn = ((*v)[panel_c_[q]] - (*v)[panel_a_[q]]).cross(d2) + d1.cross((*v)[panel_d_[q]] - (*v)[panel_b_[q]]);
    const Vec3 turning = inverse * unit.cross(dn);
    f[3] = turning.x();
    f[4] = turning.y();
    f[5] = turning.z();
  }
}

// Inlined into both callers, so that it is compiled in each of their clones (x86-64-v3 and the baseline).
[[gnu::always_inline]] inline void FoldKernel::block(std::size_t h0, std::size_t count, const Points& p, const Points* v, const double* frames,
                              double* theta, double* rate, double* y, double* x) const {
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t h = h0 + i;
    const double* fa = frames + 6 * first_[h];
    const double* fb = frames + 6 * second_[h];
    const Vec3 na(fa[0], fa[1], fa[2]), nb(fb[0], fb[1], fb[2]);
    // With n_B's sign s and e = r_kj / |r_kj|: y = e . (n_A x s n_B) = (s / |r_kj|) r_kj . (n_A x n_B).
    const double scaled = signed_inverse_length_[h];
    const Vec3 r = p[k_[h]] - p[j_[h]];
    y[i] = scaled * r.dot(na.cross(nb));
    x[i] = std::copysign(1.0, scaled) * na.dot(nb);
    if (!v) continue;
    // d theta / dt: the panels' relative turning rate about the hinge (e runs j to k).
    rate[i] = std::abs(scaled) * r.dot(Vec3(fb[3] - fa[3], fb[4] - fa[4], fb[5] - fa[5]));
  }
  atan2_many(y, x, theta, count);
}

namespace {
// Four arrays of it: 8 KiB, in the first cache level. A multiple of 4: atan2_many
// takes four at a time and the rest one by one (the two round differently), so
// every fold gets the same one in angles() and energy(), whatever the block.
constexpr std::size_t block_size = 256;
static_assert(block_size % 4 == 0);
}  // namespace

PHEDRA_CPU_CLONES void FoldKernel::angles(const Points& p, const Points* v, double* theta, double* rate,
                                          std::vector<double>& frames) const {
  panel_frames(p, v, frames);
  double y[block_size], x[block_size];
  for (std::size_t h0 = 0; h0 < size(); h0 += block_size) {
    block(h0, std::min(block_size, size() - h0), p, v, frames.data(), theta + h0, v ? rate + h0 : nullptr, y, x);
  }
}

PHEDRA_CPU_CLONES FoldKernel::Sums FoldKernel::energy(const Points& p, const Points* v, const double* reference,
                                                      const double* rest, const double* weight, double* angles,
                                                      std::int8_t* turns, std::vector<double>& frames) const {
  panel_frames(p, v, frames);
  const double turn = 2.0 * std::numbers::pi, per_turn = 1.0 / turn;
  const double shifter = 0x1.8p52;  // x + shifter - shifter: x rounded to a whole number (|x| < 2^51)
  double y[block_size], x[block_size], theta[block_size], rate[block_size];
  // Four partial sums of each (no chain of additions each waiting for the one
  // before): summed at the end.
  constexpr std::size_t lanes = 4;
  double energy_sum[lanes] = {}, rate_sum[lanes] = {}, largest[lanes] = {};
  for (std::size_t h0 = 0; h0 < size(); h0 += block_size) {
    const std::size_t count = std::min(block_size, size() - h0);
    block(h0, count, p, v, frames.data(), theta, rate, y, x);
    if (!v) std::fill(rate, rate + count, 0.0);
    const std::size_t whole_lanes = count / lanes * lanes;
    for (std::size_t i = 0; i < count; i += lanes) {
      const std::size_t width = i < whole_lanes ? lanes : count - i;
      for (std::size_t l = 0; l < width; ++l) {
        const std::size_t h = h0 + i + l;
        const double raw = theta[i + l];
        double whole;
        if (reference) {
          whole = ((reference[h] - raw) * per_turn + shifter) - shifter;
          turns[h] = static_cast<std::int8_t>(whole);
        } else {
          whole = turns[h];
        }
        const double continuous = raw + turn * whole;
        if (reference) largest[l] = std::max(largest[l], std::abs(continuous - reference[h]));
        angles[h] = continuous;
        const double d = continuous - rest[h], wd = weight[h] * d;
        energy_sum[l] += wd * d;
        rate_sum[l] += wd * rate[i + l];
      }
    }
  }
  Sums out;
  out.energy = 0.5 * ((energy_sum[0] + energy_sum[1]) + (energy_sum[2] + energy_sum[3]));
  out.rate = (rate_sum[0] + rate_sum[1]) + (rate_sum[2] + rate_sum[3]);
  out.largest = std::max(std::max(largest[0], largest[1]), std::max(largest[2], largest[3]));
  return out;
}

}  // namespace phedra
