#include "phedra/self_intersection.h"

#include "collision_detector.h"

#include "phedra/bisection.h"
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

using detail::CollisionDetector;
using detail::two_pi;

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
  std::optional<Collision> hit = detector.shut_hinge(x, t);
  return hit ? hit : detector.panels(x, t);
}

double collision_margin_at_t_star(const Design& design, const Collision& c) {
  const CollisionDetector detector(design, {});
  const Points x = detector.positions(design.assembly.t_star());
  if (c.kind == Collision::Kind::hinge) {
    const std::optional<double> angle = detector.opening_between(c.a.face, c.b.face, x);
    return angle ? std::min(*angle, two_pi - *angle) : std::numeric_limits<double>::quiet_NaN();
  }
  return -detector.deepest(x).second / design.assembly.model_size();
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
