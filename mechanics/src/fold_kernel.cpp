#include "fold_kernel.h"

#include "vector_atan2.h"

#include "phedra/cpu_clones.h"
#include "phedra/errors.h"

#include <cmath>

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
    inverse_length_.push_back(1.0 / hinge.length);
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
    sign_.push_back(along > 0.0 ? 1.0 : -1.0);
  }
}

PHEDRA_CPU_CLONES void FoldKernel::angles(const Points& p, const Points* v, double* theta, double* rate, double* y, double* x,
                        std::vector<double>& frames) const {
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
  const std::size_t n = size();
  const double* frame = frames.data();
  for (std::size_t h = 0; h < n; ++h) {
    const double* fa = frame + 6 * first_[h];
    const double* fb = frame + 6 * second_[h];
    const Vec3 na(fa[0], fa[1], fa[2]);
    const Vec3 nb = sign_[h] * Vec3(fb[0], fb[1], fb[2]);
    const Vec3& xj = p[j_[h]];
    const Vec3 e = inverse_length_[h] * (p[k_[h]] - xj);
    const Vec3 c = na.cross(nb);
    y[h] = e.dot(c);
    x[h] = na.dot(nb);
    if (!v) continue;
    // d theta / dt: the panels' relative turning rate about the hinge (e runs j to k).
    rate[h] = e.dot(Vec3(fb[3] - fa[3], fb[4] - fa[4], fb[5] - fa[5]));
  }
  atan2_many(y, x, theta, n);
}

}  // namespace phedra
