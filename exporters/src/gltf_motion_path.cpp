#include "gltf_parts.h"

#include "phedra/errors.h"

#include <algorithm>
#include <memory>

namespace phedra::gltf {
namespace {

Points y_up(Points p) {
  for (Vec3& x : p) x = to_y_up(x);
  return p;
}

/// A path over the segments of `time`, segment k on the branch `flipped[k]` (empty: the input branch).
MotionPath segment_path(const Assembly& a, const AssemblyMesh& mesh, TimeMap time,
                        std::vector<std::vector<bool>> flipped) {
  auto map = std::make_shared<const TimeMap>(std::move(time));
  auto branches = std::make_shared<const std::vector<std::vector<bool>>>(std::move(flipped));
  MotionPath path;
  path.time = *map;
  path.lo = 0.0;
  path.hi = static_cast<double>(map->segments.size());
  path.minimum_keyframes = 2 * map->segments.size() + 1;
  auto segment = [map](double u) {
    return std::min(static_cast<std::size_t>(std::max(u, 0.0)), map->segments.size() - 1);
  };
  path.seconds_of = [map, segment](double u) {
    const TimeSegment& s = map->segments[segment(u)];
    const double phi = std::clamp(u - static_cast<double>(segment(u)), 0.0, 1.0);
    return s.start + phi * (s.end - s.start);
  };
  path.t_of = [map, segment, seconds = path.seconds_of](double u) { return map->segments[segment(u)].t_at(seconds(u)); };
  path.positions = [&a, &mesh, branches, segment, t_of = path.t_of](double u) {
    AssemblyConfiguration c;
    const std::vector<bool>& branch = (*branches)[segment(u)];
    if (branch.empty()) {
      a.evaluate(t_of(u), c);
    } else {
      a.evaluate(t_of(u), branch, c);
    }
    return y_up(mesh.positions(c));
  };
  path.positions_at_t = [&a, &mesh](double t) { return y_up(mesh.positions(a.evaluate(t))); };
  return path;
}

/// Whether t is a flexion limit of the design (within rounding of the interval's width).
bool at_flexion_limit(const Assembly& a, double t) {
  const FlexionInterval& f = a.flexion_interval();
  const double slack = 1e-12 * std::max(1.0, std::abs(f.upper.t - f.lower.t));
  return std::abs(t - f.lower.t) <= slack || std::abs(t - f.upper.t) <= slack;
}

}  // namespace

MotionPath interval_path(const Design& design, const AssemblyMesh& mesh, const GltfOptions& options) {
  const Assembly& a = design.assembly;
  const double lo = options.range ? options.range->first : a.flexion_interval().lower.t;
  const double hi = options.range ? options.range->second : a.flexion_interval().upper.t;
  TimeSegment s;
  s.start = 0.0;
  s.end = options.seconds;
  s.t0 = lo;
  s.t1 = hi;
  const double ease = options.ease * options.seconds;
  s.ease0 = ease_at_end(at_flexion_limit(a, lo), ease, options.seconds);
  s.ease1 = ease_at_end(at_flexion_limit(a, hi), ease, options.seconds);
  TimeMap time;
  time.segments = {s};
  time.ping_pong = options.ping_pong;
  MotionPath path = segment_path(a, mesh, time, {std::vector<bool>{}});
  path.minimum_keyframes = 2;
  path.rest = hi > lo ? std::clamp(s.seconds_at(a.t_star()) / options.seconds, 0.0, 1.0) : 0.0;
  return path;
}

MotionPath cycle_path(const Design& design, const AssemblyMesh& mesh, const GltfOptions& options) {
  const Assembly& a = design.assembly;
  if (options.static_t) throw InvalidInputError("--cycle", "a static export (--at) has no cycle");
  if (options.range) {
    throw InvalidInputError("--cycle", "the configuration curve runs through the flexion limits; it cannot be "
                                       "restricted to a sub-interval (--no-self-intersection)");
  }
  const std::vector<PHedron::Pass>& passes = a.base().configuration_cycle().passes;
  const double width = a.flexion_interval().width();
  TimeMap time;
  time.ping_pong = options.ping_pong;
  std::vector<std::vector<bool>> flipped;
  double start = 0.0;
  for (const PHedron::Pass& p : passes) {
    TimeSegment s;
    s.start = start;
    s.end = start + std::abs(p.to - p.from) / width * options.seconds;
    s.t0 = p.from;
    s.t1 = p.to;
    const double ease = options.ease * options.seconds;
    s.ease0 = ease_at_end(at_flexion_limit(a, p.from), ease, s.end - s.start);
    s.ease1 = ease_at_end(at_flexion_limit(a, p.to), ease, s.end - s.start);
    time.segments.push_back(s);
    flipped.push_back(p.flipped);
    start = s.end;
  }
  MotionPath path = segment_path(a, mesh, time, flipped);
  path.rest = 0.0;
  return path;
}

}  // namespace phedra::gltf
