#include "phedra/hinge_pins.h"

#include "phedra/box_tree.h"
#include "phedra/solid_crossing.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <utility>

namespace phedra {
namespace {

/// A prism of a profile between z0 and z1 of a frame (origin, x, y, z: right-handed).
struct Frame {
  Vec3 origin, x, y, z;
  Vec3 at(const Vec2& p, double h) const { return origin + p.x() * x + p.y() * y + h * z; }
};

/// A closed solid: the profile's outer loop (counter-clockwise) and, optionally,
/// a circular hole of the inner loop's points at the angles of `arc` (the outer
/// loop's arc part), extruded from z0 to z1. `cap` lists the cap's triangles as
/// indices into outer (0..n-1) then inner (n..).
Solid prism(const Frame& f, const std::vector<Vec2>& outer, const std::vector<Vec2>& inner,
            const std::vector<std::array<std::size_t, 3>>& cap, double z0, double z1) {
  Solid s;
  const std::size_t n = outer.size(), m = inner.size(), loop = n + m;
  for (const double h : {z0, z1}) {
    for (const Vec2& p : outer) s.vertices.push_back(f.at(p, h));
    for (const Vec2& p : inner) s.vertices.push_back(f.at(p, h));
  }
  for (const auto& t : cap) {
    s.triangles.push_back({t[0], t[2], t[1]});                       // bottom: facing -z
    s.triangles.push_back({loop + t[0], loop + t[1], loop + t[2]});  // top: facing +z
  }
  auto wall = [&](std::size_t first, std::size_t count, bool outward) {
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t a = first + k, b = first + (k + 1) % count;
      if (outward) {
        s.triangles.push_back({a, b, loop + b});
        s.triangles.push_back({a, loop + b, loop + a});
      } else {
        s.triangles.push_back({a, loop + b, b});
        s.triangles.push_back({a, loop + a, loop + b});
      }
    }
  };
  wall(0, n, true);
  wall(n, m, false);
  return s;
}

/// A knuckle's profile: a disc of radius R around the hinge line with a hole of
/// radius r, joined to the leaf [0, W] x [-t, 0] (x into its plate, y towards the
/// plate side). Outer loop: (R, 0), the arc counter-clockwise to
/// (sqrt(R^2 - t^2), -t), (W, -t), (W, 0); the hole at the arc's angles.
Solid knuckle(const Frame& f, const PinSizes& p, double z0, double z1, bool hole = true) {
  const double R = p.knuckle_radius, r = p.hole_radius, t = p.leaf_thickness, W = p.leaf_reach;
  const double end = 2.0 * M_PI - std::asin(t / R);
  const std::size_t steps = 32;
  // The hole's polygon around the circle of radius r (no side nearer the axis;
  // its corners at the arc's angles and one half way across the leaf's gap),
  // the pin's inside the pin's circle: the pin's play is at least r less the
  // pin's radius everywhere.
  const double closing = 2.0 * M_PI - end;
  const double around = r / std::cos(std::max(0.5 * end / static_cast<double>(steps), 0.25 * closing));
  std::vector<Vec2> outer, inner;
  for (std::size_t k = 0; k <= steps; ++k) {
    const double a = end * static_cast<double>(k) / static_cast<double>(steps);
    outer.emplace_back(R * std::cos(a), R * std::sin(a));
    inner.emplace_back(around * std::cos(a), around * std::sin(a));
  }
  outer.emplace_back(W, -t);
  outer.emplace_back(W, 0.0);
  const std::size_t n = outer.size();
  std::vector<std::array<std::size_t, 3>> cap;
  if (!hole) {  // printed in place around its pin: the profile whole, a fan from (R, 0) (it sees every corner)
    for (std::size_t k = 1; k + 1 < n; ++k) cap.push_back({0, k, k + 1});
    return prism(f, outer, {}, cap, z0, z1);
  }
  for (std::size_t k = 0; k < steps; ++k) {  // the ring between the arc and the hole
    cap.push_back({k, k + 1, n + k + 1});
    cap.push_back({k, n + k + 1, n + k});
  }
  // The rest, a fan from the hole's corner across the leaf's gap (it sees every
  // corner): the hole's last point, the arc's end, the leaf's corners, the arc's
  // start, the hole's first point.
  inner.emplace_back(around * std::cos(end + 0.5 * closing), around * std::sin(end + 0.5 * closing));
  const std::array<std::size_t, 7> rest{n + steps + 1, n + steps, steps, steps + 1, steps + 2, 0, n};
  for (std::size_t k = 1; k + 1 < rest.size(); ++k) cap.push_back({rest[0], rest[k], rest[k + 1]});
  return prism(f, outer, inner, cap, z0, z1);
}

Solid pin(const Frame& f, double radius, double z0, double z1) {
  const std::size_t steps = 24;
  std::vector<Vec2> outer;
  for (std::size_t k = 0; k < steps; ++k) {
    const double a = 2.0 * M_PI * static_cast<double>(k) / static_cast<double>(steps);
    outer.emplace_back(radius * std::cos(a), radius * std::sin(a));
  }
  std::vector<std::array<std::size_t, 3>> cap;
  for (std::size_t k = 1; k + 1 < steps; ++k) cap.push_back({0, k, k + 1});
  return prism(f, outer, {}, cap, z0, z1);
}

}  // namespace

PinSizes::PinSizes(double thickness)
    : knuckle_radius(0.5 * thickness),
      pin_radius(0.2 * thickness),
      hole_radius(0.25 * thickness),
      clearance(0.08 * thickness),
      leaf_thickness(0.3 * thickness),
      leaf_reach(0.5 * thickness + 0.08 * thickness + 2.0 * thickness),
      knuckle_length(3.0 * thickness) {}

PrinterProfile fdm_printer() { return PrinterProfile{"fdm", 0.4, 0.8, 0.3, 2.0, 0.4}; }
PrinterProfile sla_printer() { return PrinterProfile{"sla", 0.05, 0.3, 0.15, 1.0, 0.2}; }

double thinnest_printable_mm(const PrinterProfile& printer, std::string* binding, bool in_place) {
  const PinSizes unit(1.0);  // the sizes per unit thickness
  const double wall = std::max(printer.smallest_feature_mm, 2.0 * printer.nozzle_mm);
  auto mm = [](double x) {
    std::string text = std::to_string(x);
    text.erase(text.find_last_not_of('0') + 1);
    if (text.back() == '.') text.pop_back();
    return text;
  };
  const std::pair<double, std::string> needs[] = {
      {printer.pin_mm / (2.0 * unit.pin_radius), "a pin " + mm(printer.pin_mm) + " mm across is 0.4 T"},
      {printer.clearance_mm / unit.clearance, "a clearance of " + mm(printer.clearance_mm) + " mm between parts is 0.08 T"},
      {printer.gap_mm / unit.clearance, "a gap of " + mm(printer.gap_mm) + " mm between knuckles is 0.08 T"},
      {wall / (unit.knuckle_radius - unit.hole_radius), "a knuckle's wall of " + mm(wall) + " mm is 0.25 T"},
      {wall / unit.leaf_thickness, "a leaf " + mm(wall) + " mm thick is 0.3 T"},
      {0.5 * printer.clearance_mm / (unit.hole_radius - unit.pin_radius),
       "a pin's play of " + mm(0.5 * printer.clearance_mm) + " mm in its hole is 0.05 T"},
      // Printed in place, the pin and the knuckles turning on it are printed apart by its play.
      {in_place ? printer.clearance_mm / (unit.hole_radius - unit.pin_radius) : 0.0,
       "a pin's play of " + mm(printer.clearance_mm) + " mm in its hole, printed in place, is 0.05 T"},
  };
  double t = 0.0;
  for (const auto& [need, why] : needs) {
    if (need > t) {
      t = need;
      if (binding) *binding = why;
    }
  }
  return t;
}

double pin_hinge_gap(double thickness) {
  const PinSizes p(thickness);
  return 2.0 * (p.knuckle_radius + p.clearance);
}

namespace {

using Edge = std::pair<std::size_t, std::size_t>;

/// The hinges with a plate on both sides: mesh edge (lower vertex first) -> its two faces.
std::map<Edge, std::vector<std::size_t>> hinge_sides(const ThickPlates& plates) {
  const AssemblyMesh& mesh = plates.mesh();
  std::map<Edge, std::vector<std::size_t>> sides;
  for (std::size_t k = 0; k < plates.plates(); ++k) {
    const std::size_t face = plates.panel(k);
    const auto& q = mesh.faces[face];
    for (std::size_t c = 0; c < 4; ++c) {
      const std::size_t a = q[c], b = q[(c + 1) % 4];
      if (a != b) sides[{std::min(a, b), std::max(a, b)}].push_back(face);
    }
  }
  for (auto it = sides.begin(); it != sides.end();) it = it->second.size() == 2 ? std::next(it) : sides.erase(it);
  return sides;
}

/// The base margin at each end of a hinge of `length`: a tenth of it, at most T.
double base_margin(double length, double thickness) { return std::min(0.1 * length, thickness); }

/// The parts of every hinge at x with the layout's margins; `hinge_of[k]`: the
/// hinge (index into `edges`) of part k, `plate_of[k]`: the face a knuckle's
/// leaf is glued to (none for pins).
HingeParts build_parts(const ThickPlates& plates, const Points& x, const std::vector<Edge>& edges,
                       const std::map<Edge, std::vector<std::size_t>>& sides, const PinLayout& layout,
                       std::vector<std::size_t>* hinge_of, std::vector<std::size_t>* plate_of, bool in_place = false) {
  const PinSizes p(plates.thickness());
  const AssemblyMesh& mesh = plates.mesh();
  constexpr std::size_t none = static_cast<std::size_t>(-1);
  auto centroid = [&](std::size_t face) {
    Vec3 c = Vec3::Zero();
    for (std::size_t v : mesh.faces[face]) c += x[v];
    return Vec3(c / 4.0);
  };
  auto plate_side = [&](std::size_t face) {  // the unit normal towards the plate
    const auto& q = mesh.faces[face];
    const Vec3 n = (x[q[2]] - x[q[0]]).cross(x[q[3]] - x[q[1]]).normalized();
    return Vec3(plates.side() == PlateSide::back ? -n : n);
  };
  HingeParts parts;
  std::vector<Solid> pins;
  std::vector<std::string> pin_names;
  std::vector<std::size_t> pin_hinges, pin_bodies;
  for (std::size_t h = 0; h < edges.size(); ++h) {
    const Edge& edge = edges[h];
    const std::vector<std::size_t>& faces = sides.at(edge);
    const Vec3 u = x[edge.first], v = x[edge.second];
    const double length = (v - u).norm();
    const auto found = layout.margins.find(edge);
    const double base = base_margin(length, plates.thickness());
    const std::array<double, 2> margin = found != layout.margins.end() ? found->second : std::array<double, 2>{base, base};
    const double span = length - margin[0] - margin[1];
    if (!(span > 3.0 * p.clearance)) continue;
    ++parts.hinges;
    const std::size_t count = std::clamp<std::size_t>(2 * static_cast<std::size_t>(std::round(std::max(0.0, 0.5 * (span / p.knuckle_length - 1.0)))) + 1, 3, 15);
    const double segment = span / static_cast<double>(count);
    // Each plate's frame: x into the plate (across the hinge line), y towards its
    // plate side, z along the hinge (turned so that the frame is right-handed).
    auto frame_of = [&](std::size_t face) {
      Frame f;
      f.origin = u;
      f.z = (v - u) / length;
      Vec3 in = centroid(face) - u;
      f.x = (in - in.dot(f.z) * f.z).normalized();
      f.y = f.z.cross(f.x);
      if (f.y.dot(plate_side(face)) < 0.0) {  // along the hinge the other way
        f.origin = v;
        f.z = -f.z;
        f.y = -f.y;
      }
      return f;
    };
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t face = faces[k % 2], other = faces[1 - k % 2];
      const Frame f = frame_of(face);
      // Along the hinge from u: this knuckle's piece of the span, parted from its neighbours by the clearance.
      double a = margin[0] + static_cast<double>(k) * segment + (k > 0 ? 0.5 * p.clearance : 0.0);
      double b = margin[0] + static_cast<double>(k + 1) * segment - (k + 1 < count ? 0.5 * p.clearance : 0.0);
      if (f.origin != u) std::tie(a, b) = std::pair{length - b, length - a};
      parts.solids.push_back(knuckle(f, p, a, b, !(in_place && face == faces[0])));
      parts.names.push_back("knuckle_" + std::to_string(face) + "_" + std::to_string(other) + "_" + std::to_string(k + 1));
      if (hinge_of) hinge_of->push_back(h);
      if (plate_of) plate_of->push_back(face);
      parts.body.push_back(face);
      ++parts.knuckles;
    }
    Frame along{u, Vec3::Zero(), Vec3::Zero(), (v - u) / length};
    along.x = frame_of(faces[0]).x;
    along.y = along.z.cross(along.x);
    pins.push_back(pin(along, p.pin_radius, margin[0], length - margin[1]));
    pin_names.push_back("pin_" + std::to_string(faces[0]) + "_" + std::to_string(faces[1]));
    pin_hinges.push_back(h);
    pin_bodies.push_back(faces[0]);
    ++parts.pins;
  }
  for (std::size_t k = 0; k < pins.size(); ++k) {
    parts.solids.push_back(std::move(pins[k]));
    parts.names.push_back(std::move(pin_names[k]));
    if (hinge_of) hinge_of->push_back(pin_hinges[k]);
    if (plate_of) plate_of->push_back(none);
    parts.body.push_back(pin_bodies[k]);
  }
  return parts;
}

/// The parts and plates of one configuration, each with its boxes; part k
/// (k < parts) of hinge hinge_of[k], a knuckle glued to plate own_plate[k]
/// (none for pins); the plates after the parts.
struct Configuration {
  HingeParts parts;
  std::vector<Solid> plate_solids;
  std::vector<OrientedSolid> oriented;
  std::vector<Box> boxes;
  std::vector<std::size_t> hinge_of, own_plate;
  std::vector<std::size_t> body;  ///< the plate each solid moves with
  std::size_t n = 0;  ///< parts

  Configuration(const ThickPlates& plates, const Points& x, const std::vector<Edge>& edges,
                const std::map<Edge, std::vector<std::size_t>>& sides, const PinLayout& layout,
                const std::map<std::size_t, std::size_t>& plate_index) {
    std::vector<std::size_t> face_of;
    parts = build_parts(plates, x, edges, sides, layout, &hinge_of, &face_of, layout.in_place);
    plate_solids = plates.solids(x);
    n = parts.solids.size();
    for (const std::size_t face : face_of) own_plate.push_back(face == none ? none : plate_index.at(face));
    for (const std::size_t face : parts.body) body.push_back(plate_index.at(face));
    for (std::size_t k = 0; k < plate_solids.size(); ++k) body.push_back(k);
    for (const Solid& s : parts.solids) oriented.push_back(orient(s));
    for (const Solid& s : plate_solids) oriented.push_back(orient(s));
    for (const OrientedSolid& o : oriented) boxes.push_back(o.box);
  }
  Configuration(const Configuration&) = delete;  // `oriented` points into the solids
  Configuration& operator=(const Configuration&) = delete;
  static constexpr std::size_t none = static_cast<std::size_t>(-1);

  /// Calls visit(i, j, depth) for every two solids (i < j, at least one a part)
  /// cutting into each other deeper than `tolerance`, but one hinge's own parts
  /// (apart by design) and a knuckle with its own plate (glued); `skip(i, j)`
  /// leaves more pairs out.
  template <class Skip, class Visit>
  void crossings(double tolerance, Skip&& skip, Visit&& visit) const {
    BoxTree(boxes).for_each_pair([&](std::size_t i, std::size_t j) {
      if (j >= n && i >= n) return true;  // two plates: the thick check's
      if (j < n && hinge_of[i] == hinge_of[j]) return true;
      if (j >= n && own_plate[i] == j - n) return true;
      if (skip(i, j)) return true;
      const double depth = solids_penetration(oriented[i], oriented[j], tolerance);
      if (depth > tolerance) visit(i, j, depth);
      return true;
    });
  }

  /// Calls visit(i, j, gap) for every two solids moving with different plates
  /// (two plates too) closer than `clearance`, but one hinge's own parts (their
  /// clearances are the design's); `skip(i, j)` leaves more pairs out.
  template <class Skip, class Visit>
  void gaps(double clearance, Skip&& skip, Visit&& visit) const {
    std::vector<Box> grown;
    for (const Box& b : boxes) grown.push_back({(b.lo.array() - 0.5 * clearance).matrix(), (b.hi.array() + 0.5 * clearance).matrix()});
    BoxTree(grown).for_each_pair([&](std::size_t i, std::size_t j) {
      if (body[i] == body[j]) return true;
      if (j < n && hinge_of[i] == hinge_of[j]) return true;
      if (skip(i, j)) return true;
      const double gap = solids_gap(oriented[i], oriented[j], clearance);
      if (gap < clearance) visit(i, j, gap);
      return true;
    });
  }
};

}  // namespace

double in_place_clearance(double thickness) {
  const PinSizes p(thickness);
  return p.hole_radius - p.pin_radius;
}

PinLayout pin_layout(const ThickPlates& plates, const std::vector<double>& ts, std::optional<InPlace> in_place) {
  const std::map<Edge, std::vector<std::size_t>> sides = hinge_sides(plates);
  std::vector<Edge> edges;
  for (const auto& [edge, faces] : sides) edges.push_back(edge);
  PinLayout layout;
  layout.in_place = in_place.has_value();
  std::vector<double> configurations = ts;
  if (in_place) configurations.push_back(in_place->t);
  const double T = plates.thickness();
  const double tolerance = 1e-9 * plates.design().assembly.model_size();
  std::map<std::size_t, std::size_t> plate_index;  // face -> plate
  for (std::size_t k = 0; k < plates.plates(); ++k) plate_index[plates.panel(k)] = k;
  std::vector<double> lengths;
  {
    const Points x = plates.positions(plates.design().assembly.t_star());
    for (const Edge& e : edges) {
      const double length = (x[e.second] - x[e.first]).norm();
      lengths.push_back(length);
      layout.margins[e] = {base_margin(length, T), base_margin(length, T)};
    }
  }
  const PinSizes p(T);
  constexpr std::size_t rounds = 16;
  // Only pairs with a part of a hinge whose margins changed can cross anew (the
  // others were found apart): every hinge in the first round.
  std::vector<bool> changed(edges.size(), true);
  for (layout.rounds = 0; layout.rounds < rounds; ++layout.rounds) {
    std::set<std::pair<std::size_t, int>> grow;  // (hinge, end)
    for (std::size_t c = 0; c < configurations.size(); ++c) {
      const Points x = plates.positions(configurations[c]);
      const Configuration at(plates, x, edges, sides, layout, plate_index);
      const std::size_t n = at.n;
      auto room = [&](std::size_t h) {
        const auto& m = layout.margins.at(edges[h]);
        return lengths[h] - m[0] - m[1];
      };
      // The end of part i's hinge nearer to `point`.
      auto end_near = [&](std::size_t i, const Vec3& point) {
        const Edge& e = edges[at.hinge_of[i]];
        const Vec3 u = x[e.first], d = x[e.second] - u;
        return (point - u).dot(d) < 0.5 * d.squaredNorm() ? 0 : 1;
      };
      auto unchanged = [&](std::size_t i, std::size_t j) {
        return !changed[at.hinge_of[i]] && !(j < n && changed[at.hinge_of[j]]);
      };
      auto move_back = [&](std::size_t i, std::size_t j, double) {
        // The part to move back: of two hinges, the one with more room left (the
        // other keeps its knuckles); a part cutting into a plate.
        const Box& bi = at.boxes[i];
        const Box& bj = at.boxes[j];
        const Vec3 centre = 0.5 * (bi.lo.cwiseMax(bj.lo) + bi.hi.cwiseMin(bj.hi));
        std::size_t k = i;
        if (j < n && room(at.hinge_of[j]) > room(at.hinge_of[i])) k = j;
        grow.insert({at.hinge_of[k], end_near(k, centre)});
      };
      if (c < ts.size()) {
        at.crossings(tolerance, unchanged, move_back);
      } else {  // printed in place at this t: parts of different plates the clearance apart (two plates: said by pin_gaps)
        at.gaps(in_place->clearance, [&](std::size_t i, std::size_t j) { return i >= n || unchanged(i, j); }, move_back);
      }
    }
    if (grow.empty()) break;
    std::fill(changed.begin(), changed.end(), false);
    for (const auto& [h, end] : grow) {
      changed[h] = true;
      double& m = layout.margins[edges[h]][static_cast<std::size_t>(end)];
      m += std::max(0.5 * T, 0.5 * m);
    }
  }
  for (std::size_t h = 0; h < edges.size(); ++h) {
    const auto& m = layout.margins[edges[h]];
    if (!(lengths[h] - m[0] - m[1] > 3.0 * p.clearance)) ++layout.without_knuckles;
  }
  return layout;
}

HingeParts pin_hinge_parts(const ThickPlates& plates, const Points& x, const PinLayout& layout) {
  const std::map<Edge, std::vector<std::size_t>> sides = hinge_sides(plates);
  std::vector<Edge> edges;
  for (const auto& [edge, faces] : sides) edges.push_back(edge);
  return build_parts(plates, x, edges, sides, layout, nullptr, nullptr, layout.in_place);
}

std::vector<PinCrossing> pin_gaps(const ThickPlates& plates, const PinLayout& layout, double t, double clearance) {
  const std::map<Edge, std::vector<std::size_t>> sides = hinge_sides(plates);
  std::vector<Edge> edges;
  for (const auto& [edge, faces] : sides) edges.push_back(edge);
  std::map<std::size_t, std::size_t> plate_index;
  for (std::size_t k = 0; k < plates.plates(); ++k) plate_index[plates.panel(k)] = k;
  const Configuration at(plates, plates.positions(t), edges, sides, layout, plate_index);
  auto name = [&](std::size_t i) { return i < at.n ? at.parts.names[i] : "plate_" + std::to_string(plates.panel(i - at.n)); };
  std::vector<PinCrossing> found;
  at.gaps(clearance, [](std::size_t, std::size_t) { return false; },
          [&](std::size_t i, std::size_t j, double gap) { found.push_back({name(i), name(j), t, gap}); });
  return found;
}

InPlaceBodies in_place_bodies(const ThickPlates& plates, std::vector<Solid> plate_solids, const HingeParts& parts) {
  InPlaceBodies out;
  std::map<std::size_t, std::size_t> plate_index;
  for (std::size_t k = 0; k < plates.plates(); ++k) {
    plate_index[plates.panel(k)] = k;
    out.names.push_back("body_" + std::to_string(plates.panel(k)));
  }
  out.solids = std::move(plate_solids);
  out.shells.assign(out.solids.size(), 1);
  for (std::size_t k = 0; k < parts.solids.size(); ++k) {
    const std::size_t b = plate_index.at(parts.body[k]);
    Solid& into = out.solids[b];
    const std::size_t base = into.vertices.size();
    into.vertices.insert(into.vertices.end(), parts.solids[k].vertices.begin(), parts.solids[k].vertices.end());
    for (const auto& tri : parts.solids[k].triangles) into.triangles.push_back({base + tri[0], base + tri[1], base + tri[2]});
    ++out.shells[b];
  }
  return out;
}

std::vector<double> pin_configurations(double t_star, double lower, double upper, std::size_t samples) {
  std::vector<double> ts{t_star};
  for (std::size_t k = 0; k < samples; ++k) {
    const double f = samples == 1 ? 0.0 : static_cast<double>(k) / static_cast<double>(samples - 1);
    ts.push_back(k + 1 == samples ? upper : lower + f * (upper - lower));
  }
  return ts;
}

std::vector<PinCrossing> pin_crossings(const ThickPlates& plates, const PinLayout& layout, const std::vector<double>& ts) {
  const std::map<Edge, std::vector<std::size_t>> sides = hinge_sides(plates);
  std::vector<Edge> edges;
  for (const auto& [edge, faces] : sides) edges.push_back(edge);
  std::map<std::size_t, std::size_t> plate_index;
  for (std::size_t k = 0; k < plates.plates(); ++k) plate_index[plates.panel(k)] = k;
  const double tolerance = 1e-9 * plates.design().assembly.model_size();
  std::vector<PinCrossing> found;
  for (const double t : ts) {
    const Configuration at(plates, plates.positions(t), edges, sides, layout, plate_index);
    auto name = [&](std::size_t i) {
      return i < at.n ? at.parts.names[i] : "plate_" + std::to_string(plates.panel(i - at.n));
    };
    at.crossings(tolerance, [](std::size_t, std::size_t) { return false; },
                 [&](std::size_t i, std::size_t j, double depth) { found.push_back({name(i), name(j), t, depth}); });
  }
  return found;
}

}  // namespace phedra
