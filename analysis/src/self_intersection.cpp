#include "phedra/self_intersection.h"

#include "phedra/errors.h"
#include "phedra/number_format.h"

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
  std::array<std::size_t, 2> far_a{}, far_b{};  ///< the other corners of each face
};

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
    std::map<std::pair<std::size_t, std::size_t>, std::vector<std::pair<std::size_t, int>>> edges;
    for (std::size_t k = 0; k < valid_.size(); ++k) {
      const Quad& q = mesh_.faces[valid_[k]];
      for (int c = 0; c < 4; ++c) {
        const std::size_t u = q[c], v = q[(c + 1) % 4];
        edges[{std::min(u, v), std::max(u, v)}].push_back({k, c});
      }
    }
    for (const auto& [edge, faces] : edges) {
      for (std::size_t i = 0; i < faces.size(); ++i) {
        for (std::size_t j = i + 1; j < faces.size(); ++j) {
          const Quad& qa = mesh_.faces[valid_[faces[i].first]];
          const Quad& qb = mesh_.faces[valid_[faces[j].first]];
          const int ca = faces[i].second, cb = faces[j].second;
          hinges_.push_back({faces[i].first, faces[j].first, edge.first, edge.second,
                             {qa[(ca + 2) % 4], qa[(ca + 3) % 4]}, {qb[(cb + 2) % 4], qb[(cb + 3) % 4]}});
          adjacent_.push_back(key(faces[i].first, faces[j].first));
        }
      }
    }
    std::sort(adjacent_.begin(), adjacent_.end());
    // Broad-phase cell: the mean panel extent (panels are rigid: it never changes).
    double sum = 0.0, largest = 0.0;
    for (std::size_t f : valid_) {
      const auto [lo, hi] = box(f, x);
      const double extent = (hi - lo).maxCoeff();
      sum += extent;
      largest = std::max(largest, extent);
    }
    cell_ = valid_.empty() ? 1.0 : std::max(sum / static_cast<double>(valid_.size()), largest / 16.0);
    if (!(cell_ > 0.0)) cell_ = 1.0;
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
      Vec3 a = 0.5 * (x[h.far_a[0]] + x[h.far_a[1]]) - x[h.v0];
      Vec3 b = 0.5 * (x[h.far_b[0]] + x[h.far_b[1]]) - x[h.v0];
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

  /// The deepest penetration of any two panels at x (0 when none).
  double deepest(const Points& x) const {
    double d = 0.0;
    for_each_penetration(x, [&](std::size_t f, std::size_t g) {
      d = std::max(d, depth(valid_[f], valid_[g], x));
      return true;
    });
    return d;
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
    struct Entry {
      std::array<long long, 3> cell;
      std::size_t face;
    };
    std::vector<std::pair<Vec3, Vec3>> boxes(valid_.size());
    std::vector<Entry> entries;
    entries.reserve(valid_.size() * 2);
    for (std::size_t k = 0; k < valid_.size(); ++k) {
      boxes[k] = box(valid_[k], x);
      boxes[k].first.array() -= tolerance_;
      boxes[k].second.array() += tolerance_;
      const auto lo = cell_of(boxes[k].first), hi = cell_of(boxes[k].second);
      for (long long i = lo[0]; i <= hi[0]; ++i) {
        for (long long j = lo[1]; j <= hi[1]; ++j) {
          for (long long l = lo[2]; l <= hi[2]; ++l) entries.push_back({{i, j, l}, k});
        }
      }
    }
    std::sort(entries.begin(), entries.end(), [](const Entry& p, const Entry& q) {
      return p.cell != q.cell ? p.cell < q.cell : p.face < q.face;
    });
    for (std::size_t begin = 0; begin < entries.size();) {
      std::size_t end = begin;
      while (end < entries.size() && entries[end].cell == entries[begin].cell) ++end;
      for (std::size_t i = begin; i < end; ++i) {
        for (std::size_t j = i + 1; j < end; ++j) {
          const std::size_t f = entries[i].face, g = entries[j].face;
          const auto& [flo, fhi] = boxes[f];
          const auto& [glo, ghi] = boxes[g];
          if ((flo.array() > ghi.array()).any() || (glo.array() > fhi.array()).any()) continue;
          // Test each pair once: in the cell holding the low corner of the boxes' overlap.
          if (cell_of(flo.cwiseMax(glo)) != entries[i].cell) continue;
          if (std::binary_search(adjacent_.begin(), adjacent_.end(), key(f, g))) continue;
          if (penetrate(valid_[f], valid_[g], x) && !visit(f, g)) return;
        }
      }
      begin = end;
    }
  }

  static std::pair<std::size_t, std::size_t> key(std::size_t a, std::size_t b) { return {std::min(a, b), std::max(a, b)}; }

  PanelCorners corners(std::size_t f, const Points& x) const {
    const Quad& q = mesh_.faces[f];
    return {x[q[0]], x[q[1]], x[q[2]], x[q[3]]};
  }

  std::pair<Vec3, Vec3> box(std::size_t f, const Points& x) const {
    const Quad& q = mesh_.faces[f];
    Vec3 lo = x[q[0]], hi = x[q[0]];
    for (int c = 1; c < 4; ++c) {
      lo = lo.cwiseMin(x[q[c]]);
      hi = hi.cwiseMax(x[q[c]]);
    }
    return {lo, hi};
  }

  std::array<long long, 3> cell_of(const Vec3& p) const {
    return {static_cast<long long>(std::floor(p.x() / cell_)), static_cast<long long>(std::floor(p.y() / cell_)),
            static_cast<long long>(std::floor(p.z() / cell_))};
  }

  bool penetrate(std::size_t f, std::size_t g, const Points& x) const { return depth(f, g, x) > tolerance_; }

  /// How deeply two panels cut into each other (triangle_penetration of their triangles).
  double depth(std::size_t f, std::size_t g, const Points& x) const {
    const auto tf = panel_triangles(corners(f, x));
    const auto tg = panel_triangles(corners(g, x));
    double deepest = -std::numeric_limits<double>::infinity();
    for (const Triangle& p : tf) {
      for (const Triangle& q : tg) deepest = std::max(deepest, triangle_penetration(p, q));
    }
    return deepest;
  }

  PanelId id(std::size_t f) const { return panel_id(assembly_, mesh_, f); }

  static constexpr double angle_tolerance = 1e-9;
  const Assembly& assembly_;
  AssemblyMesh mesh_;
  double tolerance_ = 0.0;
  double cell_ = 1.0;
  std::vector<std::size_t> valid_;
  std::vector<InvalidPanel> invalid_;
  std::vector<Hinge> hinges_;
  std::vector<std::pair<std::size_t, std::size_t>> adjacent_;
  mutable AssemblyConfiguration configuration_;
};

/// Walks from t* towards `end`; returns the first collision (t = the last free t).
/// A collision that starts at `end` itself (within 1e-9 of the interval) is a
/// contact at the limit: returned in `contact`, and the free interval reaches `end`.
std::optional<Collision> sweep(const CollisionDetector& detector, double end, std::size_t samples,
                               const std::vector<double>& openings_at_t_star, double& free_end,
                               std::optional<Collision>& contact) {
  const double t_star = detector.assembly().t_star();
  const double width = detector.assembly().flexion_interval().width();
  free_end = t_star;
  if (end == t_star) return std::nullopt;
  std::vector<double> good_openings = openings_at_t_star, next;
  double good = t_star;
  for (std::size_t k = 1; k <= samples; ++k) {
    const double s = 1.0 - static_cast<double>(k) / static_cast<double>(samples);
    const double t = k == samples ? end : t_star + (end - t_star) * (1.0 - s * s);
    const Points x = detector.positions(t);
    std::optional<Collision> hit = detector.continue_hinges(x, good_openings, next, t);
    if (!hit) hit = detector.panels(x, t);
    if (!hit) {
      good = t;
      good_openings = next;
      free_end = t;
      continue;
    }
    // Bisect [good, bad] down to 1e-12 of the interval's width.
    double bad = t;
    for (int iteration = 0; iteration < 80 && std::abs(bad - good) > 1e-12 * width; ++iteration) {
      const double mid = 0.5 * (good + bad);
      const Points xm = detector.positions(mid);
      std::optional<Collision> h = detector.continue_hinges(xm, good_openings, next, mid);
      if (!h) h = detector.panels(xm, mid);
      if (h) {
        bad = mid;
        hit = h;
      } else {
        good = mid;
        good_openings = next;
      }
    }
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
  return {{"kind", c->kind == Collision::Kind::hinge ? "hinge" : "panels"},
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
  AssemblyConfiguration c;
  a.evaluate(a.t_star(), c);
  const Points x = mesh.positions(c);
  std::vector<InvalidPanel> out;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Quad& q = mesh.faces[f];
    const PanelShape shape = panel_shape({x[q[0]], x[q[1]], x[q[2]], x[q[3]]});
    if (!is_valid_panel(shape)) out.push_back({panel_id(a, mesh, f), shape});
  }
  return out;
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
    r.depth_at_t_star = detector.deepest(x);
    return r;
  }
  r.upper = sweep(detector, r.t_mu, options.samples_per_side, openings, r.free_upper, r.upper_contact);
  r.lower = sweep(detector, r.t_lambda, options.samples_per_side, openings, r.free_lower, r.lower_contact);
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
  out << "flexion interval [" << format_number(r.t_lambda) << ", " << format_number(r.t_mu)
      << "], t* = " << format_number(r.t_star) << '\n';
  const bool several = r.members > 1;
  if (r.at_t_star) {
    out << "the configuration at t* intersects itself: " << describe_collision(*r.at_t_star, several, false) << '\n';
  } else if (r.intersection_free()) {
    out << "intersection-free over the whole flexion interval\n";
  } else {
    out << "intersection-free on [" << format_number(r.free_lower) << ", " << format_number(r.free_upper) << "]\n";
    if (r.lower) out << "  below " << format_number(r.lower->t) << ": " << describe_collision(*r.lower, several, false) << '\n';
    if (r.upper) out << "  above " << format_number(r.upper->t) << ": " << describe_collision(*r.upper, several, false) << '\n';
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
