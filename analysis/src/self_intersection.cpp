#include "phedra/self_intersection.h"

#include "phedra/panel_size.h"

#include "phedra/bisection.h"
#include "phedra/box_tree.h"
#include "phedra/errors.h"
#include "phedra/number_format.h"
#include "phedra/panel_nets.h"

#include <exception>
#ifndef __EMSCRIPTEN__
#include <thread>
#endif
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <ostream>

namespace phedra {
namespace {

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
Vec3 into_face(const Points& x, const Quad& q, int corner) {
  Vec3 area = Vec3::Zero();
  for (int k = 0; k < 4; ++k) area += x[q[k]].cross(x[q[(k + 1) % 4]]);
  return area.cross(x[q[(corner + 1) % 4]] - x[q[corner]]);
}

/// The faces, hinges and broad phase of one design's merged mesh.
class CollisionDetector {
 public:
  CollisionDetector(const Design& design, const SelfIntersectionOptions& options)
      : assembly_(design.assembly), mesh_(panel_mesh(design)) {
    tolerance_ = options.relative_tolerance * assembly_.model_size();
    const Points x = positions(assembly_.t_star());
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

  const Assembly& assembly() const { return assembly_; }
  const std::vector<InvalidPanel>& invalid() const { return invalid_; }
  std::size_t panels() const { return mesh_.faces.size(); }
  std::size_t hinges() const { return hinges_.size(); }

  Points positions(double t) const {
    assembly_.evaluate(t, configuration_);
    return mesh_.positions(configuration_);
  }

  /// Opening angle of every hinge in [0, 2 pi): pi is flat, 0 and 2 pi folded onto each other.
  std::vector<double> openings(const Points& x) const {
    std::vector<double> out;
    out.reserve(hinges_.size());
    for (const Hinge& h : hinges_) {
      const Vec3 e = (x[h.v1] - x[h.v0]).normalized();
      Vec3 a = into_face(x, h.quad_a, h.corner_a);
      Vec3 b = into_face(x, h.quad_b, h.corner_b);
      a -= e.dot(a) * e;
      b -= e.dot(b) * e;
      double angle = std::atan2(e.dot(a.cross(b)), a.dot(b));
      if (angle < 0.0) angle += two_pi;
      out.push_back(angle);
    }
    return out;
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

  PanelId id(std::size_t f) const { return panel_id(assembly_, mesh_, f); }

 public:
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
  const Assembly& assembly_;
  AssemblyMesh mesh_;
  double tolerance_ = 0.0;
  std::vector<std::size_t> valid_;
  std::vector<InvalidPanel> invalid_;
  std::vector<Hinge> hinges_;
  std::vector<std::vector<std::size_t>> neighbours_;  ///< per valid panel: the valid panels it shares an edge with
  mutable AssemblyConfiguration configuration_;
  mutable std::vector<PanelFrame> frames_;  ///< of the valid panels, at the configuration being tested
};

/// Walks from t* towards `end`; returns the first collision (t = the last free t).
/// A collision that starts at `end` itself (within 1e-9 of the interval) is a
/// contact at the limit: returned in `contact`, and the free interval reaches `end`.
std::optional<Collision> sweep(const CollisionDetector& detector, double end, std::size_t samples,
                               const std::vector<double>& openings_at_t_star, double max_growth, double& free_end,
                               std::optional<Collision>& contact) {
  const double t_star = detector.assembly().t_star();
  const double width = detector.assembly().flexion_interval().width();
  free_end = t_star;
  if (end == t_star) return std::nullopt;
  auto sample_t = [&](std::size_t k) {
    const double s = 1.0 - static_cast<double>(k) / static_cast<double>(samples);
    return k >= samples ? end : t_star + (end - t_star) * (1.0 - s * s);
  };
  std::vector<double> good_openings = openings_at_t_star, next;
  double good = t_star;
  Points x_good = detector.positions(t_star);
  const double limit = max_growth > 0.0 ? max_growth * bounding_diagonal(x_good) : std::numeric_limits<double>::infinity();
  for (std::size_t k = 1; k <= samples; ++k) {
    const double t = sample_t(k);
    const Points x = detector.positions(t);
    std::optional<Collision> hit = detector.grown(x, t, limit, max_growth);
    if (!hit) hit = detector.continue_hinges(x, good_openings, next, t);
    if (!hit) hit = detector.panels(x, t);
    if (!hit) {
      good = t;
      good_openings = next;
      x_good = x;
      free_end = t;
      continue;
    }
    // Bisect [good, bad] down to 1e-12 of the interval's width, testing only
    // the panels that come close between the two.
    const auto pairs = detector.close_pairs(x_good, x);
    hit = bisect_first_hit(good, t, 1e-12 * width, *hit, [&](double mid) {
      const Points xm = detector.positions(mid);
      std::optional<Collision> h = detector.grown(xm, mid, limit, max_growth);
      if (!h) h = detector.continue_hinges(xm, good_openings, next, mid);
      if (!h) h = detector.panels_among(xm, mid, pairs);
      if (!h) good_openings = next;
      return h;
    });
    hit->t = good;
    if (std::abs(end - good) <= 1e-9 * width) {
      free_end = end;
      contact = hit;
      return std::nullopt;
    }
    free_end = good;
    return hit;
  }
  return std::nullopt;
}

std::string describe_collision(const Collision& c, bool several_members, bool contact) {
  const std::string pair = describe(c.a, several_members) + " and " + describe(c.b, several_members);
  if (c.kind == Collision::Kind::growth) {
    return "the design grows past " + format_human(c.growth) + " times its size at t* (bounding-box diagonal; --max-growth), " +
           describe(c.a, several_members) + " furthest out";
  }
  if (c.kind == Collision::Kind::hinge) {
    return "the hinge between " + pair + (contact ? " folds flat (the panels touch, no more)" : " folds shut and through");
  }
  return pair + (contact ? " touch (no more)" : " penetrate");
}

nlohmann::json panel_json(const PanelId& p) {
  nlohmann::json j{{"face", p.face}, {"member", p.member}, {"strip", p.row}, {"column", p.column}};
  if (p.shared_with) j["shared_with_member"] = p.shared_with->member;
  return j;
}

nlohmann::json collision_json(const std::optional<Collision>& c) {
  if (!c) return nullptr;
  const char* kind = c->kind == Collision::Kind::hinge ? "hinge" : c->kind == Collision::Kind::growth ? "growth" : "panels";
  return {{"kind", kind},
          {"t", c->t},
          {"panels", {panel_json(c->a), panel_json(c->b)}}};
}

}  // namespace

PanelId panel_id(const Assembly& assembly, const AssemblyMesh& mesh, std::size_t f) {
  const std::size_t m = mesh.face_member[f], local = mesh.face_local[f];
  const std::size_t columns = assembly.topology(m).face_columns();
  return {f, m, local / columns, local % columns, mesh.face_shared_with[f]};
}

std::string describe(const PanelId& p, bool several_members) {
  std::string s = "panel " + std::to_string(p.face) + " (";
  if (several_members) s += "member " + std::to_string(p.member) + ", ";
  s += "strip " + std::to_string(p.row) + ", column " + std::to_string(p.column);
  if (p.shared_with) s += "; the wall it shares with member " + std::to_string(p.shared_with->member);
  return s + ")";
}

std::vector<InvalidPanel> invalid_panels(const Design& design) {
  const Assembly& a = design.assembly;
  const AssemblyMesh mesh = panel_mesh(design);
  const std::vector<PanelShape> shapes = panel_shapes(a, mesh);
  std::vector<InvalidPanel> out;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (!is_valid_panel(shapes[f])) out.push_back({panel_id(a, mesh, f), shapes[f]});
  }
  return out;
}

MotionMargins motion_margins(const Design& design, double from, double to, std::size_t samples_per_side,
                             const SelfIntersectionOptions& options) {
  const CollisionDetector detector(design, options);
  const Assembly& a = design.assembly;
  const double t_star = a.t_star();
  const FlexionInterval& f = a.flexion_interval();
  MotionMargins m;
  m.t_depth = m.t_folded = t_star;
  m.folded = -std::numeric_limits<double>::infinity();
  auto look = [&](const Points& x, const std::vector<double>& openings, double t) {
    const auto [depth, sum] = detector.deepest(x);
    if (depth > m.depth) {
      m.depth = depth;
      m.t_depth = t;
    }
    m.depth_sum = std::max(m.depth_sum, sum);
    for (double o : openings) {
      const double past = std::max(-o, o - two_pi);  // how far past shut (0 or 360 degrees)
      if (past > m.folded) {
        m.folded = past;
        m.t_folded = t;
      }
    }
  };
  const Points x0 = detector.positions(t_star);
  const double size_at_star = bounding_diagonal(x0);
  const std::vector<double> start = detector.openings(x0);
  look(x0, start, t_star);
  for (const double end : {to, from}) {
    if (end == t_star) continue;
    const bool limit = end == f.lower.t || end == f.upper.t;
    std::vector<double> openings = start, next;
    const std::size_t n = std::max<std::size_t>(samples_per_side, 1);
    for (std::size_t k = 1; k <= n; ++k) {
      const double s = 1.0 - static_cast<double>(k) / static_cast<double>(limit ? n + 1 : n);
      const double t = k == n && !limit ? end : t_star + (end - t_star) * (1.0 - s * s);
      const Points x = detector.positions(t);
      detector.continue_hinges(x, openings, next, t);
      openings.swap(next);
      look(x, openings, t);
      if (size_at_star > 0.0) m.growth = std::max(m.growth, bounding_diagonal(x) / size_at_star);
    }
  }
  if (!std::isfinite(m.folded)) m.folded = -std::numbers::pi;  // no hinges
  return m;
}

std::vector<std::size_t> colliding_panels(const Design& design, double t, std::size_t steps,
                                          const SelfIntersectionOptions& options) {
  const CollisionDetector detector(design, options);
  const double t_star = design.assembly.t_star();
  std::vector<double> openings = detector.openings(detector.positions(t_star)), next;
  const std::size_t count = std::max<std::size_t>(steps, 1);
  for (std::size_t k = 1; k <= count; ++k) {
    const double s = static_cast<double>(k) / static_cast<double>(count);
    detector.continue_hinges(detector.positions(t_star + s * (t - t_star)), openings, next, t);
    openings.swap(next);
  }
  std::vector<std::size_t> out = detector.all_penetrating(detector.positions(t));
  const std::vector<std::size_t> folded = detector.hinge_panels(openings);
  out.insert(out.end(), folded.begin(), folded.end());
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

SelfIntersectionReport find_self_intersections(const Design& design, const SelfIntersectionOptions& options) {
  if (options.samples_per_side < 1) throw InvalidInputError("--samples", "at least one sample a side");
  const CollisionDetector detector(design, options);
  const Assembly& a = design.assembly;
  SelfIntersectionReport r;
  r.name = a.name();
  r.t_star = a.t_star();
  r.t_lambda = a.flexion_interval().lower.t;
  r.t_mu = a.flexion_interval().upper.t;
  r.free_lower = r.free_upper = r.t_star;
  r.invalid_panels = detector.invalid();
  r.panels = detector.panels();
  r.hinges = detector.hinges();
  r.samples = options.samples_per_side;
  r.members = a.member_count();
  r.model_size = a.model_size();
  const Points x = detector.positions(r.t_star);
  const std::vector<double> openings = detector.openings(x);
  std::vector<double> unused;
  r.at_t_star = detector.continue_hinges(x, openings, unused, r.t_star);
  if (!r.at_t_star) r.at_t_star = detector.panels(x, r.t_star);
  if (r.at_t_star) {
    r.depth_at_t_star = detector.deepest(x).first;
    return r;
  }
  // The two sides are independent: on large designs the lower one runs on a
  // second thread with its own detector (a detector keeps scratch; evaluating
  // the assembly is thread-safe once its shared vertices are known). Not in
  // WebAssembly, which is built without threads.
#ifndef __EMSCRIPTEN__
  if (r.panels >= 2000) {
    a.shared_vertices();
    const CollisionDetector second(design, options);
    std::exception_ptr failure;
    std::thread lower([&] {
      try {
        r.lower = sweep(second, r.t_lambda, options.samples_per_side, openings, options.max_growth, r.free_lower, r.lower_contact);
      } catch (...) {
        failure = std::current_exception();
      }
    });
    try {
      r.upper = sweep(detector, r.t_mu, options.samples_per_side, openings, options.max_growth, r.free_upper, r.upper_contact);
    } catch (...) {
      lower.join();
      throw;
    }
    lower.join();
    if (failure) std::rethrow_exception(failure);
    return r;
  }
#endif
  r.upper = sweep(detector, r.t_mu, options.samples_per_side, openings, options.max_growth, r.free_upper, r.upper_contact);
  r.lower = sweep(detector, r.t_lambda, options.samples_per_side, openings, options.max_growth, r.free_lower, r.lower_contact);
  return r;
}

std::string describe(const Collision& collision, bool several_members, bool contact) {
  return describe_collision(collision, several_members, contact);
}

std::optional<Collision> self_intersection_at_t_star(const Design& design, const SelfIntersectionOptions& options) {
  const CollisionDetector detector(design, options);
  const double t = design.assembly.t_star();
  const Points x = detector.positions(t);
  const std::vector<double> openings = detector.openings(x);
  std::vector<double> unused;
  std::optional<Collision> hit = detector.continue_hinges(x, openings, unused, t);
  return hit ? hit : detector.panels(x, t);
}

std::pair<double, double> intersection_free_interval(const SelfIntersectionReport& r) {
  if (r.at_t_star) {
    throw InvalidInputError("--no-self-intersection", "the configuration at t* = " + format_number(r.t_star) +
                                                          " already intersects itself: " + describe_collision(*r.at_t_star, r.members > 1, false));
  }
  return {r.free_lower, r.free_upper};
}

nlohmann::json SelfIntersectionReport::to_json() const {
  nlohmann::json invalid = nlohmann::json::array();
  for (const InvalidPanel& p : invalid_panels) {
    nlohmann::json j = panel_json(p.panel);
    j["shape"] = to_string(p.shape);
    invalid.push_back(j);
  }
  return {{"name", name},
          {"t_star", t_star},
          {"flexion_interval", {t_lambda, t_mu}},
          {"intersection_free", intersection_free()},
          {"free_interval", at_t_star ? nlohmann::json(nullptr) : nlohmann::json{free_lower, free_upper}},
          {"at_t_star", collision_json(at_t_star)},
          {"lower", collision_json(lower)},
          {"upper", collision_json(upper)},
          {"lower_contact", collision_json(lower_contact)},
          {"upper_contact", collision_json(upper_contact)},
          {"invalid_panels", invalid},
          {"depth_at_t_star", depth_at_t_star},
          {"panels", panels},
          {"hinges", hinges},
          {"samples_per_side", samples},
          {"model_size", model_size}};
}

std::ostream& operator<<(std::ostream& out, const SelfIntersectionReport& r) {
  out << "self-intersection of \"" << r.name << "\": " << r.panels << " panels, " << r.hinges << " hinges, "
      << r.samples << " samples from t* to each limit\n";
  out << "flexion interval [" << format_human(r.t_lambda) << ", " << format_human(r.t_mu)
      << "], t* = " << format_human(r.t_star) << '\n';
  const bool several = r.members > 1;
  if (r.at_t_star) {
    out << "the configuration at t* intersects itself: " << describe_collision(*r.at_t_star, several, false) << '\n';
  } else if (r.intersection_free()) {
    out << "intersection-free over the whole flexion interval\n";
  } else {
    out << "intersection-free on [" << format_human(r.free_lower) << ", " << format_human(r.free_upper) << "]\n";
    if (r.lower) out << "  below " << format_human(r.lower->t) << ": " << describe_collision(*r.lower, several, false) << '\n';
    if (r.upper) out << "  above " << format_human(r.upper->t) << ": " << describe_collision(*r.upper, several, false) << '\n';
  }
  if (r.lower_contact) out << "  at t_lambda: " << describe_collision(*r.lower_contact, several, true) << '\n';
  if (r.upper_contact) out << "  at t_mu: " << describe_collision(*r.upper_contact, several, true) << '\n';
  if (!r.invalid_panels.empty()) {
    out << r.invalid_panels.size() << (r.invalid_panels.size() == 1 ? " panel is" : " panels are")
        << " not simple (left out of the collision test)\n";
  }
  return out;
}

}  // namespace phedra
