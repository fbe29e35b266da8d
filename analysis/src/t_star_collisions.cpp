#include "phedra/t_star_collisions.h"

#include "collision_detector.h"

#include "phedra/box_tree.h"
#include "phedra/panel_shape.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace phedra {
namespace detail {

/// What the panel mesh of a design depends on: with the same structure, two
/// designs have the same mesh (faces, vertex references, shared walls).
struct MeshStructure {
  bool merge = false;
  std::vector<std::array<std::size_t, 3>> members;  ///< rows, columns, cyclic
  std::vector<std::vector<VertexRef>> shared;

  explicit MeshStructure(const Design& design) : merge(design.merge) {
    const Assembly& a = design.assembly;
    for (std::size_t m = 0; m < a.member_count(); ++m) {
      const GridTopology& t = a.topology(m);
      members.push_back({t.rows(), t.columns(), t.cyclic() ? 1u : 0u});
    }
    shared = a.shared_vertices();
  }
  bool operator==(const MeshStructure&) const = default;
};

}  // namespace detail

namespace {

/// How far apart two point sets lie along `axis`: the gap between their
/// projections (<= 0: they overlap along it).
double gap_along(const Vec3& axis, const PanelCorners& a, const PanelCorners& b) {
  double a_lo = std::numeric_limits<double>::infinity(), a_hi = -a_lo, b_lo = a_lo, b_hi = -a_lo;
  for (int k = 0; k < 4; ++k) {
    const double pa = axis.dot(a[k]), pb = axis.dot(b[k]);
    a_lo = std::min(a_lo, pa);
    a_hi = std::max(a_hi, pa);
    b_lo = std::min(b_lo, pb);
    b_hi = std::max(b_hi, pb);
  }
  return std::max(b_lo - a_hi, a_lo - b_hi);
}

}  // namespace

struct TStarCollisions::State {
  detail::MeshStructure structure;
  detail::CollisionDetector detector;
  Points reference;  ///< positions at t* when the list was made
  bool hinges_open = false;  ///< no hinge was shut there
  double margin = 0.0;
  double margin_factor = 0.1;  ///< of the median panel's box diagonal (smaller after a list too long)
  struct Pair {
    std::uint32_t k = 0, l = 0;  ///< valid panels
    float gap = 0.0f;            ///< the certificate, rounded down (<= 0: none, tested every time)
  };
  std::vector<Pair> pairs;
  // scratch
  std::vector<double> moved;          ///< per valid panel: how far its corners moved since
  std::vector<std::uint8_t> unmoved;  ///< per valid panel: not at all
  std::vector<Vec3> normals;
  std::vector<std::uint8_t> framed;
};

namespace {

/// How far a panel reaches to the less-reached side of a plane through `origin`
/// with unit normal `n` (as the narrow phase's first test: <= its tolerance, no collision).
double straddle(const Vec3& n, const Vec3& origin, const PanelCorners& b) {
  double above = -std::numeric_limits<double>::infinity(), below = above;
  for (const Vec3& c : b) {
    const double d = n.dot(c - origin);
    above = std::max(above, d);
    below = std::max(below, -d);
  }
  return std::min(above, below);
}

float rounded_down(double gap) {
  const float f = static_cast<float>(gap);
  return static_cast<double>(f) > gap ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}

}  // namespace

TStarCollisions::TStarCollisions(const SelfIntersectionOptions& options) : options_(options) {}
TStarCollisions::~TStarCollisions() = default;
TStarCollisions::TStarCollisions(TStarCollisions&&) noexcept = default;
TStarCollisions& TStarCollisions::operator=(TStarCollisions&&) noexcept = default;

std::optional<Collision> TStarCollisions::check(const Design& design) {
  last_ = {};
  const double t = design.assembly.t_star();
  Points x;
  detail::MeshStructure structure(design);
  bool rebuild = !state_ || !(state_->structure == structure) || !state_->detector.rebind(design, options_, x);
  if (rebuild) {
    state_.reset(new State{std::move(structure), detail::CollisionDetector(design, options_), {}, false, 0.0, 0.1, {}, {}, {}, {}, {}});
    x = state_->detector.positions(t);
  }
  State& s = *state_;
  const detail::CollisionDetector& d = s.detector;
  const std::vector<std::size_t>& valid = d.valid();
  const std::vector<Quad>& faces = d.mesh().faces;
  const std::size_t n = valid.size();
  double furthest = 0.0;
  if (!rebuild) {
    s.moved.assign(n, 0.0);
    s.unmoved.assign(n, 0);
    for (std::size_t k = 0; k < n; ++k) {
      double m = 0.0;
      for (std::size_t v : faces[valid[k]]) m = std::max(m, (x[v] - s.reference[v]).squaredNorm());
      s.moved[k] = std::sqrt(m);
      s.unmoved[k] = m == 0.0;
      furthest = std::max(furthest, s.moved[k]);
    }
    // Pairs off the list were over `margin` apart: with every corner moved by
    // less than half of it they still are (no margin: no list kept).
    rebuild = !(2.0 * furthest < s.margin);
  }
  last_.rebuilt = rebuild;
  if (rebuild) {
    std::optional<Collision> first = d.shut_hinge(x, t);
    // The list: every pair whose boxes, grown by half the margin, overlap; the
    // margin a tenth of the median panel's box diagonal, less when that
    // made a list of over 100 pairs a panel (then none is kept this time).
    std::vector<Box> boxes(n), grown(n);
    std::vector<double> sizes(n);
    for (std::size_t k = 0; k < n; ++k) {
      boxes[k] = d.valid_box(k, x);
      sizes[k] = (boxes[k].hi - boxes[k].lo).norm();
    }
    s.margin = 0.0;
    if (!sizes.empty()) {
      std::nth_element(sizes.begin(), sizes.begin() + static_cast<std::ptrdiff_t>(sizes.size() / 2), sizes.end());
      s.margin = s.margin_factor * sizes[sizes.size() / 2];
    }
    const double grow = 0.5 * s.margin + d.tolerance();
    for (std::size_t k = 0; k < n; ++k) {
      grown[k] = boxes[k];
      grown[k].lo.array() -= grow;
      grown[k].hi.array() += grow;
    }
    std::vector<PanelCorners> corners(n);
    s.normals.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      corners[k] = d.valid_corners(k, x);
      s.normals[k] = quad_normal(corners[k]);
    }
    d.prepare_frames(x);
    s.pairs.clear();
    const std::size_t most = 100 * n;
    bool kept = true;
    BoxTree(grown).for_each_pair([&](std::size_t k, std::size_t l) {
      if (d.hinged(k, l)) return true;
      // Separated along a normal or a coordinate axis (the boxes).
      double gap = std::max(gap_along(s.normals[k], corners[k], corners[l]), gap_along(s.normals[l], corners[k], corners[l]));
      for (int c = 0; c < 3; ++c) gap = std::max({gap, boxes[l].lo[c] - boxes[k].hi[c], boxes[k].lo[c] - boxes[l].hi[c]});
      const float certificate = rounded_down(gap);
      if (kept && s.pairs.size() == most) {
        kept = false;
        s.pairs = {};
      }
      if (kept) s.pairs.push_back({static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(l), certificate});
      if (certificate > 0.0f) {
        ++last_.certified;
      } else {
        ++last_.tested;
        if (!first && d.penetration(k, l) > d.tolerance()) first = d.panel_collision(k, l, t);
      }
      return true;
    });
    if (kept) {
      s.margin_factor = 0.1;  // (the next list tries the usual margin again)
    } else {
      s.margin = 0.0;  // the next check makes the list again, with a smaller margin
      s.margin_factor *= 0.25;
    }
    s.reference = std::move(x);
    s.hinges_open = !first || first->kind != Collision::Kind::hinge;
    last_.pairs = s.pairs.size();
    return first;
  }
  last_.pairs = s.pairs.size();
  if (std::optional<Collision> hit = d.shut_hinge(x, t, s.hinges_open ? &s.unmoved : nullptr)) return hit;
  // Each pair: its certificate, else the narrow phase's cheap plane tests, then all of it.
  s.normals.resize(n);
  s.framed.assign(n, 0);
  auto normal = [&](std::uint32_t k) -> const Vec3& {
    if (!(s.framed[k] & 1)) {
      s.normals[k] = quad_normal(d.valid_corners(k, x));
      s.framed[k] |= 1;
    }
    return s.normals[k];
  };
  for (const State::Pair& p : s.pairs) {
    if (p.gap > s.moved[p.k] + s.moved[p.l]) {
      ++last_.certified;
      continue;
    }
    ++last_.tested;
    const PanelCorners ca = d.valid_corners(p.k, x), cb = d.valid_corners(p.l, x);
    if (!(straddle(normal(p.k), ca[0], cb) > d.tolerance()) || !(straddle(normal(p.l), cb[0], ca) > d.tolerance())) continue;
    for (const std::uint32_t f : {p.k, p.l}) {
      if (!(s.framed[f] & 2)) {
        d.prepare_frames(x, f);
        s.framed[f] |= 2;
      }
    }
    if (d.penetration(p.k, p.l) > d.tolerance()) return d.panel_collision(p.k, p.l, t);
  }
  return std::nullopt;
}

}  // namespace phedra
