#pragma once
// The collision detector of self_intersection.cpp and t_star_collisions.cpp
// (internal): one design's merged mesh, its valid panels, hinges and the narrow
// phase (panel planes, their common line, triangles), with a BoxTree broad phase.

#include "phedra/assembly_mesh.h"
#include "phedra/box_tree.h"
#include "phedra/design.h"
#include "phedra/panel_id.h"
#include "phedra/panel_nets.h"
#include "phedra/panel_shape.h"
#include "phedra/panel_size.h"
#include "phedra/self_intersection.h"
#include "phedra/triangle_overlap.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <vector>

namespace phedra::detail {

constexpr double two_pi = 2.0 * std::numbers::pi;

/// Two panels on one edge: the hinge whose opening angle is tracked.
struct Hinge {
  std::size_t a = 0, b = 0;        ///< faces (indices into the valid faces)
  std::size_t v0 = 0, v1 = 0;      ///< the edge
  Quad quad_a{}, quad_b{};         ///< the corners of each face
  int corner_a = 0, corner_b = 0;  ///< the edge is corner c to c + 1 of each face
};

/// The direction from a hinge into a face, in the face's plane: its vector area
/// (oriented by its corner order, right for darts too) crossed with the edge as
/// the face runs along it. A point of the face (the far corners' midpoint) is
/// not: a dart whose reflex corner is on the hinge can have it across the hinge
/// line, and the hinge would read shut while it is flat.
inline Vec3 into_face(const Points& x, const Quad& q, int corner) {
  Vec3 area = Vec3::Zero();
  for (int k = 0; k < 4; ++k) area += x[q[k]].cross(x[q[(k + 1) % 4]]);
  return area.cross(x[q[(corner + 1) % 4]] - x[q[corner]]);
}

/// The faces, hinges and broad phase of one design's merged mesh.
class CollisionDetector {
 public:
  CollisionDetector(const Design& design, const SelfIntersectionOptions& options)
      : CollisionDetector(design, panel_mesh(design), options) {}

  /// With the design's panel_mesh given.
  CollisionDetector(const Design& design, AssemblyMesh mesh, const SelfIntersectionOptions& options)
      : assembly_(&design.assembly), mesh_(std::move(mesh)) {
    tolerance_ = options.relative_tolerance * assembly_->model_size();
    const Points x = positions(assembly_->t_star());
    for (std::size_t f = 0; f < mesh_.faces.size(); ++f) {
      const PanelShape shape = panel_shape(corners(f, x));
      if (is_valid_panel(shape)) {
        valid_.push_back(f);
      } else {
        invalid_.push_back({id(f), shape});
      }
    }
    // Hinges: every pair of valid faces on one edge.
    neighbours_.assign(valid_.size(), {});
    std::map<std::pair<std::size_t, std::size_t>, std::vector<std::pair<std::size_t, int>>> edges;
    for (std::size_t k = 0; k < valid_.size(); ++k) {
      const Quad& q = mesh_.faces[valid_[k]];
      for (int c = 0; c < 4; ++c) {
        const std::size_t u = q[c], v = q[(c + 1) % 4];
        if (u == v) continue;  // a boundary triangle's repeated corner: no edge
        edges[{std::min(u, v), std::max(u, v)}].push_back({k, c});
      }
    }
    for (const auto& [edge, faces] : edges) {
      for (std::size_t i = 0; i < faces.size(); ++i) {
        for (std::size_t j = i + 1; j < faces.size(); ++j) {
          const Quad& qa = mesh_.faces[valid_[faces[i].first]];
          const Quad& qb = mesh_.faces[valid_[faces[j].first]];
          const int ca = faces[i].second, cb = faces[j].second;
          hinges_.push_back({faces[i].first, faces[j].first, edge.first, edge.second, qa, qb, ca, cb});
          neighbours_[faces[i].first].push_back(faces[j].first);
          neighbours_[faces[j].first].push_back(faces[i].first);
        }
      }
    }

  }

  const Assembly& assembly() const { return *assembly_; }
  const AssemblyMesh& mesh() const { return mesh_; }
  double tolerance() const { return tolerance_; }
  /// The valid panels (mesh faces): the others are left out of every test.
  const std::vector<std::size_t>& valid() const { return valid_; }

  /// The same detector for `design`, whose panel mesh is this one's (the same
  /// topology, other positions): false, and unchanged, when its panels that are
  /// valid at t* are not the same ones (the hinges would differ).
  /// `x`: the design's positions at t*.
  bool rebind(const Design& design, const SelfIntersectionOptions& options, Points& x) {
    const Assembly* before = assembly_;
    assembly_ = &design.assembly;
    x = positions(assembly_->t_star());
    std::size_t next = 0;
    for (std::size_t f = 0; f < mesh_.faces.size(); ++f) {
      const bool was_valid = next < valid_.size() && valid_[next] == f;
      if (is_valid_panel(panel_shape(corners(f, x))) != was_valid) {
        assembly_ = before;
        return false;
      }
      next += was_valid ? 1 : 0;
    }
    tolerance_ = options.relative_tolerance * assembly_->model_size();
    return true;
  }
  const std::vector<InvalidPanel>& invalid() const { return invalid_; }
  std::size_t panels() const { return mesh_.faces.size(); }
  std::size_t hinges() const { return hinges_.size(); }

  Points positions(double t) const {
    assembly_->evaluate(t, configuration_);
    return mesh_.positions(configuration_);
  }

  /// Opening angle of every hinge in [0, 2 pi): pi is flat, 0 and 2 pi folded onto each other.
  std::vector<double> openings(const Points& x) const {
    std::vector<double> out;
    out.reserve(hinges_.size());
    for (const Hinge& h : hinges_) out.push_back(opening(h, x));
    return out;
  }

  /// The opening of the hinge between mesh faces fa and fb at x (none when no
  /// hinge joins them).
  std::optional<double> opening_between(std::size_t fa, std::size_t fb, const Points& x) const {
    for (const Hinge& h : hinges_) {
      const std::size_t a = valid_[h.a], b = valid_[h.b];
      if ((a == fa && b == fb) || (a == fb && b == fa)) return opening(h, x);
    }
    return std::nullopt;
  }

  /// The first hinge folded shut at x (opening within angle_tolerance of 0 or
  /// 2 pi: the check at t*), leaving out those whose two panels (valid
  /// indices) both have `unmoved` set (their opening is the one last tested).
  std::optional<Collision> shut_hinge(const Points& x, double t, const std::vector<std::uint8_t>* unmoved = nullptr) const {
    for (const Hinge& h : hinges_) {
      if (unmoved && (*unmoved)[h.a] && (*unmoved)[h.b]) continue;
      const double angle = opening(h, x);
      if (angle <= angle_tolerance || angle >= two_pi - angle_tolerance) {
        return Collision{Collision::Kind::hinge, id(valid_[h.a]), id(valid_[h.b]), t};
      }
    }
    return std::nullopt;
  }

  /// The openings at x, continued from `previous` (each hinge turns by less than pi
  /// between the two); the first hinge that closed, if any.
  std::optional<Collision> continue_hinges(const Points& x, const std::vector<double>& previous,
                                           std::vector<double>& next, double t) const {
    const std::vector<double> raw = openings(x);
    next.resize(raw.size());
    std::optional<Collision> closed;
    for (std::size_t k = 0; k < raw.size(); ++k) {
      double step = raw[k] - std::fmod(std::fmod(previous[k], two_pi) + two_pi, two_pi);
      if (step > std::numbers::pi) step -= two_pi;
      if (step < -std::numbers::pi) step += two_pi;
      next[k] = previous[k] + step;
      if (!closed && (next[k] <= angle_tolerance || next[k] >= two_pi - angle_tolerance)) {
        closed = Collision{Collision::Kind::hinge, id(valid_[hinges_[k].a]), id(valid_[hinges_[k].b]), t};
      }
    }
    return closed;
  }

  /// The first pair of penetrating panels at x.
  std::optional<Collision> panels(const Points& x, double t) const {
    std::optional<Collision> first;
    for_each_penetration(x, [&](std::size_t f, std::size_t g) {
      first = Collision{Collision::Kind::panels, id(valid_[f]), id(valid_[g]), t};
      return false;
    });
    return first;
  }

  /// Pairs of valid panels (indices into the valid faces, not adjacent) that
  /// can meet between configurations a and b: their boxes over both, grown by
  /// the largest vertex displacement between them (times 1.5: the paths bend),
  /// overlap, and at a each reaches within that distance of the other's plane
  /// on both sides. The bisection of a collision between two close samples
  /// tests only these.
  std::vector<std::pair<std::size_t, std::size_t>> close_pairs(const Points& a, const Points& b) const {
    double moved = 0.0;
    for (std::size_t v = 0; v < a.size(); ++v) moved = std::max(moved, (a[v] - b[v]).norm());
    const double margin = 1.5 * moved + tolerance_;
    std::vector<Box> boxes(valid_.size());
    frames_.resize(valid_.size());
    for (std::size_t k = 0; k < valid_.size(); ++k) {
      const Box ba = box(valid_[k], a), bb = box(valid_[k], b);
      boxes[k] = {ba.lo.cwiseMin(bb.lo), ba.hi.cwiseMax(bb.hi)};
      boxes[k].lo.array() -= margin;
      boxes[k].hi.array() += margin;
      frames_[k] = frame(valid_[k], a);
    }
    std::vector<std::pair<std::size_t, std::size_t>> out;
    BoxTree(boxes).for_each_pair([&](std::size_t f, std::size_t g) {
      // Planes move with their panels: a distance changes by at most twice the displacement.
      if (!adjacent(f, g) && straddle(distances(frames_[f], frames_[g])) > -2.0 * margin &&
          straddle(distances(frames_[g], frames_[f])) > -2.0 * margin) {
        out.push_back({f, g});
      }
      return true;
    });
    return out;
  }

  /// The first of `pairs` (close_pairs) whose panels penetrate at x.
  std::optional<Collision> panels_among(const Points& x, double t,
                                        const std::vector<std::pair<std::size_t, std::size_t>>& pairs) const {
    frames_.resize(valid_.size());
    for (std::size_t k = 0; k < valid_.size(); ++k) frames_[k] = frame(valid_[k], x);
    for (const auto& [f, g] : pairs) {
      if (depth(f, g) > tolerance_) return Collision{Collision::Kind::panels, id(valid_[f]), id(valid_[g]), t};
    }
    return std::nullopt;
  }

  /// The deepest penetration of any two panels at x (0 when none), and the sum
  /// of the penetrations of every penetrating pair.
  std::pair<double, double> deepest(const Points& x) const {
    double d = 0.0, sum = 0.0;
    for_each_penetration(x, [&](std::size_t f, std::size_t g) {
      const double here = depth(f, g);
      d = std::max(d, here);
      sum += here;
      return true;
    });
    return {d, sum};
  }

  /// Every panel (mesh face) that penetrates another at x.
  std::vector<std::size_t> all_penetrating(const Points& x) const {
    std::vector<std::size_t> out;
    for_each_penetration(x, [&](std::size_t f, std::size_t g) {
      out.push_back(valid_[f]);
      out.push_back(valid_[g]);
      return true;
    });
    return out;
  }

  /// The mesh faces of both panels of every hinge whose (continued) opening has
  /// passed through 0 or 360 degrees (folded through; folded flat is contact).
  std::vector<std::size_t> hinge_panels(const std::vector<double>& openings) const {
    std::vector<std::size_t> out;
    for (std::size_t k = 0; k < openings.size(); ++k) {
      if (openings[k] < -angle_tolerance || openings[k] > two_pi + angle_tolerance) {  // through, not touching
        out.push_back(valid_[hinges_[k].a]);
        out.push_back(valid_[hinges_[k].b]);
      }
    }
    return out;
  }

 private:
  static double opening(const Hinge& h, const Points& x) {
    const Vec3 e = (x[h.v1] - x[h.v0]).normalized();
    Vec3 a = into_face(x, h.quad_a, h.corner_a);
    Vec3 b = into_face(x, h.quad_b, h.corner_b);
    a -= e.dot(a) * e;
    b -= e.dot(b) * e;
    double angle = std::atan2(e.dot(a.cross(b)), a.dot(b));
    if (angle < 0.0) angle += two_pi;
    return angle;
  }

  /// Calls visit(f, g) (indices into the valid faces) for each penetrating pair
  /// at x until it returns false.
  template <class Visit>
  void for_each_penetration(const Points& x, Visit&& visit) const {
    std::vector<Box> boxes(valid_.size());
    frames_.resize(valid_.size());
    for (std::size_t k = 0; k < valid_.size(); ++k) {
      boxes[k] = box(valid_[k], x);
      boxes[k].lo.array() -= tolerance_;
      boxes[k].hi.array() += tolerance_;
      frames_[k] = frame(valid_[k], x);
    }
    const BoxTree tree(boxes);
    tree.for_each_pair([&](std::size_t f, std::size_t g) {
      if (adjacent(f, g)) return true;
      return !(depth(f, g) > tolerance_) || visit(f, g);
    });
  }

  /// A panel at one configuration: its corners, plane and the two triangles it is cut into.
  struct PanelFrame {
    PanelCorners corners;
    Vec3 normal = Vec3::Zero();  ///< unit
    std::array<PreparedTriangle, 2> triangles;
  };

  PanelFrame frame(std::size_t face, const Points& x) const {
    PanelFrame p;
    p.corners = corners(face, x);
    p.normal = quad_normal(p.corners);
    const std::array<Triangle, 2> t = panel_triangles(p.corners);
    p.triangles = {prepare(t[0]), prepare(t[1])};
    return p;
  }

  /// Signed distances of b's corners from a's plane.
  static std::array<double, 4> distances(const PanelFrame& a, const PanelFrame& b) {
    std::array<double, 4> d{};
    for (int k = 0; k < 4; ++k) d[k] = a.normal.dot(b.corners[k] - a.corners[0]);
    return d;
  }

  /// How far a panel reaches to the less-reached side of a plane, from its corners'
  /// distances (<= 0: one side only).
  static double straddle(const std::array<double, 4>& d) {
    const double above = std::max({d[0], d[1], d[2], d[3]}), below = -std::min({d[0], d[1], d[2], d[3]});
    return std::min(above, below);
  }

  /// The span, along `line`, of where panel b's outline crosses the plane its
  /// corner distances `d` are measured from (a superset of b's section there).
  static std::pair<double, double> span(const PanelFrame& b, const std::array<double, 4>& d, const Vec3& line) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int k = 0; k < 4; ++k) {
      const int l = (k + 1) % 4;
      if ((d[k] <= 0.0) == (d[l] <= 0.0) && d[k] != 0.0) continue;
      const double u = d[k] == d[l] ? 0.0 : d[k] / (d[k] - d[l]);
      const double x = line.dot(b.corners[k] + u * (b.corners[l] - b.corners[k]));
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
    return {lo, hi};
  }

  /// How deeply valid panels f and g (indices into the valid faces, frames_ of
  /// the current configuration) cut into each other: triangle_penetration of
  /// their triangles, after the cheap tests that each crosses the other's plane
  /// and that their sections on the planes' common line overlap.
  double depth(std::size_t f, std::size_t g) const {
    const PanelFrame& a = frames_[f];
    const PanelFrame& b = frames_[g];
    const std::array<double, 4> db = distances(a, b);
    const double b_straddles = straddle(db);
    if (!(b_straddles > tolerance_)) return std::min(b_straddles, 0.0);
    const std::array<double, 4> da = distances(b, a);
    const double planes = std::min(b_straddles, straddle(da));
    if (!(planes > tolerance_)) return std::min(planes, 0.0);
    const Vec3 line = a.normal.cross(b.normal);
    const double sine = line.norm();
    if (sine > 1e-6) {  // (nearly parallel planes: leave it to the triangles)
      const auto [a0, a1] = span(a, da, line);
      const auto [b0, b1] = span(b, db, line);
      const double common = (std::min(a1, b1) - std::max(a0, b0)) / sine;
      if (!(common > tolerance_)) return std::min(common, 0.0);
    }
    double deepest = -std::numeric_limits<double>::infinity();
    for (const PreparedTriangle& p : a.triangles) {
      for (const PreparedTriangle& q : b.triangles) deepest = std::max(deepest, triangle_penetration(p, q));
    }
    return deepest;
  }

  /// Two valid panels share an edge (a hinge: it folds, it cannot cut).
  bool adjacent(std::size_t f, std::size_t g) const {
    const std::vector<std::size_t>& n = neighbours_[f];
    return std::find(n.begin(), n.end(), g) != n.end();
  }

  PanelCorners corners(std::size_t f, const Points& x) const {
    const Quad& q = mesh_.faces[f];
    return {x[q[0]], x[q[1]], x[q[2]], x[q[3]]};
  }

  Box box(std::size_t f, const Points& x) const {
    const Quad& q = mesh_.faces[f];
    Box b{x[q[0]], x[q[0]]};
    for (int c = 1; c < 4; ++c) {
      b.lo = b.lo.cwiseMin(x[q[c]]);
      b.hi = b.hi.cwiseMax(x[q[c]]);
    }
    return b;
  }

  PanelId id(std::size_t f) const { return panel_id(*assembly_, mesh_, f); }

 public:
  /// The narrow phase one pair at a time, on valid panels k and l (indices
  /// into valid()): prepare_frames(x) first.
  void prepare_frames(const Points& x) const {
    frames_.resize(valid_.size());
    for (std::size_t k = 0; k < valid_.size(); ++k) frames_[k] = frame(valid_[k], x);
  }
  /// Panel k's part of prepare_frames(x).
  void prepare_frames(const Points& x, std::size_t k) const {
    if (frames_.size() != valid_.size()) frames_.resize(valid_.size());
    frames_[k] = frame(valid_[k], x);
  }
  /// How deeply k and l cut into each other (> tolerance(): a collision).
  double penetration(std::size_t k, std::size_t l) const { return depth(k, l); }
  /// k and l share an edge (a hinge: never tested).
  bool hinged(std::size_t k, std::size_t l) const { return adjacent(k, l); }
  Box valid_box(std::size_t k, const Points& x) const { return box(valid_[k], x); }
  PanelCorners valid_corners(std::size_t k, const Points& x) const { return corners(valid_[k], x); }
  Collision panel_collision(std::size_t k, std::size_t l, double t) const {
    return Collision{Collision::Kind::panels, id(valid_[k]), id(valid_[l]), t};
  }

  /// The size bound: when x's bounding-box diagonal passes `limit`, a growth
  /// "collision" naming a panel of the vertex furthest from the box's centre.
  std::optional<Collision> grown(const Points& x, double t, double limit, double bound) const {
    if (!(bounding_diagonal(x) > limit)) return std::nullopt;
    Vec3 lo = x[0], hi = x[0];
    for (const Vec3& p : x) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const Vec3 centre = 0.5 * (lo + hi);
    std::size_t far = 0;
    for (std::size_t v = 1; v < x.size(); ++v) {
      if ((x[v] - centre).squaredNorm() > (x[far] - centre).squaredNorm()) far = v;
    }
    std::size_t face = 0;
    for (std::size_t f = 0; f < mesh_.faces.size(); ++f) {
      const Quad& q = mesh_.faces[f];
      if (std::find(q.begin(), q.end(), far) != q.end()) {
        face = f;
        break;
      }
    }
    Collision c{Collision::Kind::growth, id(face), id(face), t, bound};
    return c;
  }

 private:

  static constexpr double angle_tolerance = 1e-9;
  const Assembly* assembly_;
  AssemblyMesh mesh_;
  double tolerance_ = 0.0;
  std::vector<std::size_t> valid_;
  std::vector<InvalidPanel> invalid_;
  std::vector<Hinge> hinges_;
  std::vector<std::vector<std::size_t>> neighbours_;  ///< per valid panel: the valid panels it shares an edge with
  mutable AssemblyConfiguration configuration_;
  mutable std::vector<PanelFrame> frames_;  ///< of the valid panels, at the configuration being tested
};

}  // namespace phedra::detail
