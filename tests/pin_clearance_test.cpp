// Pin hinges that clear (issue 38, item 1): no two parts (plates, knuckles,
// pins) cut into each other at t*, by this test's own triangle-triangle
// crossing test over every pair of parts, a knuckle and the plate its leaf is
// glued to aside (they touch by design).

#include "phedra/box_tree.h"
#include "phedra/buildability.h"
#include "phedra/design_preset.h"
#include "phedra/hinge_pins.h"
#include "phedra/thick_plates.h"
#include "phedra/triangle_overlap.h"
#include "support/test_files.h"

#include <catch2/catch.hpp>

#include <map>
#include <string>

using namespace phedra;

namespace {

struct Crossing {
  std::string a, b;
  double depth = 0.0;
};

/// Every pair of solids that cut into each other (triangles crossing deeper
/// than `tolerance`), but a knuckle with its own plate.
std::vector<Crossing> crossings(const std::vector<Solid>& solids, const std::vector<std::string>& names,
                                const std::vector<long>& own_plate, double tolerance) {
  std::vector<Box> boxes;
  for (const Solid& s : solids) {
    Box b{s.vertices.front(), s.vertices.front()};
    for (const Vec3& v : s.vertices) b.lo = b.lo.cwiseMin(v), b.hi = b.hi.cwiseMax(v);
    boxes.push_back(b);
  }
  std::vector<Crossing> out;
  BoxTree(boxes).for_each_pair([&](std::size_t i, std::size_t j) {
    if (own_plate[i] == static_cast<long>(j) || own_plate[j] == static_cast<long>(i)) return true;
    // Each solid's triangles that reach into the other's box, each with its own box.
    auto near = [&](std::size_t a, std::size_t b) {
      std::vector<std::pair<PreparedTriangle, Box>> tris;
      for (const auto& t : solids[a].triangles) {
        const Triangle tri{solids[a].vertices[t[0]], solids[a].vertices[t[1]], solids[a].vertices[t[2]]};
        Box box{tri[0], tri[0]};
        for (const Vec3& c : tri) box.lo = box.lo.cwiseMin(c), box.hi = box.hi.cwiseMax(c);
        if (box.overlaps(boxes[b])) tris.push_back({prepare(tri), box});
      }
      return tris;
    };
    double deepest = 0.0;
    const auto ti = near(i, j), tj = near(j, i);
    for (const auto& [p, pb] : ti) {
      for (const auto& [q, qb] : tj) {
        if (pb.overlaps(qb)) deepest = std::max(deepest, triangle_penetration(p, q));
      }
    }
    if (deepest > tolerance) out.push_back({names[i], names[j], deepest});
    return true;
  });
  return out;
}

}  // namespace

TEST_CASE("pin hinges: no part cuts into another at t* nor anywhere in the thick interval", "[thick][pins]") {
  struct Case {
    std::string preset;
    double thickness;  // relative to the model size
  };
  const auto c = GENERATE(Case{"parallelogram-tube.json", 0.01}, Case{"grid-3x3.json", 0.005}, Case{"default.json", 0.005});
  {
    CAPTURE(c.preset);
    const Design design = load_design(test::presets + "/" + c.preset);
    const double size = design.assembly.model_size();
    ThickOptions options;
    options.thickness = c.thickness * size;
    options.hinge_gap = pin_hinge_gap(options.thickness);
    const ThickReport report = check_thickness(design, assess_buildability(design), options);
    const ThickPlates plates = thick_plates(design, report);
    const double t_star = design.assembly.t_star(), lower = report.thick_lower, upper = report.thick_upper;
    const PinLayout layout = pin_layout(plates, {t_star, lower, upper});
    // At t*, the thick interval's ends (where the layout was made clear) and half way to each (where it was not looked at).
    for (const double t : {t_star, lower, upper, 0.5 * (lower + t_star), 0.5 * (t_star + upper)}) {
      CAPTURE(t);
      const Points x = plates.positions(t);
      std::vector<Solid> solids = plates.solids(x);
      std::vector<std::string> names;
      std::map<std::size_t, long> plate_of_panel;
      for (std::size_t k = 0; k < plates.plates(); ++k) {
        names.push_back("plate_" + std::to_string(plates.panel(k)));
        plate_of_panel[plates.panel(k)] = static_cast<long>(k);
      }
      std::vector<long> own(solids.size(), -1);
      const HingeParts parts = pin_hinge_parts(plates, x, layout);
      for (std::size_t k = 0; k < parts.solids.size(); ++k) {
        solids.push_back(parts.solids[k]);
        names.push_back(parts.names[k]);
        long o = -1;
        if (parts.names[k].rfind("knuckle_", 0) == 0) o = plate_of_panel.at(std::stoul(parts.names[k].substr(8)));
        own.push_back(o);
      }
      const std::vector<Crossing> found = crossings(solids, names, own, 1e-9 * size);
      std::map<std::string, std::size_t> kinds;
      double deepest = 0.0;
      for (const Crossing& k : found) {
        const auto kind = [](const std::string& n) { return n.substr(0, n.find('_')); };
        ++kinds[kind(k.a) + "-" + kind(k.b)];
        deepest = std::max(deepest, k.depth / options.thickness);
      }
      CAPTURE(parts.hinges, parts.knuckles, layout.rounds, layout.without_knuckles, found.size(), deepest);
      for (const auto& [kind, count] : kinds) UNSCOPED_INFO(kind << ": " << count);
      if (!found.empty()) UNSCOPED_INFO("first: " << found.front().a << " with " << found.front().b);
      CHECK(found.empty());
      // Most hinges keep their knuckles (the rest are said by generate: tape them).
      CHECK(layout.without_knuckles * 4 <= parts.hinges + layout.without_knuckles);
    }
  }
}
