#include "phedra/hinge_pins.h"

#include <algorithm>
#include <cmath>
#include <map>
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
Solid knuckle(const Frame& f, const PinSizes& p, double z0, double z1) {
  const double R = p.knuckle_radius, r = p.hole_radius, t = p.leaf_thickness, W = p.leaf_reach;
  const double end = 2.0 * M_PI - std::asin(t / R);
  const std::size_t steps = 32;
  std::vector<Vec2> outer, inner;
  for (std::size_t k = 0; k <= steps; ++k) {
    const double a = end * static_cast<double>(k) / static_cast<double>(steps);
    outer.emplace_back(R * std::cos(a), R * std::sin(a));
    inner.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  outer.emplace_back(W, -t);
  outer.emplace_back(W, 0.0);
  const std::size_t n = outer.size();
  std::vector<std::array<std::size_t, 3>> cap;
  for (std::size_t k = 0; k < steps; ++k) {  // the ring between the arc and the hole
    cap.push_back({k, k + 1, n + k + 1});
    cap.push_back({k, n + k + 1, n + k});
  }
  // The rest, convex: the hole's last and first points, the arc's end, the leaf's corners, the arc's start.
  const std::array<std::size_t, 6> rest{n + steps, steps, steps + 1, steps + 2, 0, n};
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

double pin_hinge_gap(double thickness) {
  const PinSizes p(thickness);
  return 2.0 * (p.knuckle_radius + p.clearance);
}

HingeParts pin_hinge_parts(const ThickPlates& plates, const Points& x) {
  const PinSizes p(plates.thickness());
  const AssemblyMesh& mesh = plates.mesh();
  std::map<std::size_t, std::size_t> plate_of;  // mesh face -> plate
  for (std::size_t k = 0; k < plates.plates(); ++k) plate_of[plates.panel(k)] = k;
  // Mesh edges -> the plates on them.
  std::map<std::pair<std::size_t, std::size_t>, std::vector<std::size_t>> sides;
  for (const auto& [face, plate] : plate_of) {
    const auto& q = mesh.faces[face];
    for (std::size_t k = 0; k < 4; ++k) {
      const std::size_t a = q[k], b = q[(k + 1) % 4];
      if (a != b) sides[{std::min(a, b), std::max(a, b)}].push_back(face);
    }
  }
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
  for (const auto& [edge, faces] : sides) {
    if (faces.size() != 2) continue;
    const Vec3 u = x[edge.first], v = x[edge.second];
    const double length = (v - u).norm();
    const double margin = std::min(0.1 * length, plates.thickness());
    const double span = length - 2.0 * margin;
    if (!(span > 3.0 * p.clearance)) continue;
    ++parts.hinges;
    const std::size_t count = std::clamp<std::size_t>(2 * static_cast<std::size_t>(std::round(0.5 * (span / p.knuckle_length - 1.0))) + 1, 3, 15);
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
      double a = margin + static_cast<double>(k) * segment + (k > 0 ? 0.5 * p.clearance : 0.0);
      double b = margin + static_cast<double>(k + 1) * segment - (k + 1 < count ? 0.5 * p.clearance : 0.0);
      if (f.origin != u) std::tie(a, b) = std::pair{length - b, length - a};
      parts.solids.push_back(knuckle(f, p, a, b));
      parts.names.push_back("knuckle_" + std::to_string(face) + "_" + std::to_string(other) + "_" + std::to_string(k + 1));
      ++parts.knuckles;
    }
    Frame along{u, Vec3::Zero(), Vec3::Zero(), (v - u) / length};
    along.x = frame_of(faces[0]).x;
    along.y = along.z.cross(along.x);
    pins.push_back(pin(along, p.pin_radius, margin, length - margin));
    pin_names.push_back("pin_" + std::to_string(faces[0]) + "_" + std::to_string(faces[1]));
    ++parts.pins;
  }
  for (std::size_t k = 0; k < pins.size(); ++k) {
    parts.solids.push_back(std::move(pins[k]));
    parts.names.push_back(std::move(pin_names[k]));
  }
  return parts;
}

}  // namespace phedra
