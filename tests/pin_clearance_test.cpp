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
#include "support/cli_run.h"
#include "support/test_files.h"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

using namespace phedra;
using Catch::Matchers::Contains;

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

TEST_CASE("pin hinges for a printer: plates too thin for its parts refused with the thickness and scale that work", "[thick][pins][cli]") {
  std::string binding;
  CHECK(thinnest_printable_mm(fdm_printer(), &binding) == Approx(5.0));
  CHECK(binding == "a pin 2 mm across is 0.4 T");
  CHECK(thinnest_printable_mm(sla_printer()) == Approx(2.5));
  const std::string tube = test::presets + "/parallelogram-tube.json";
  const test::Run refused = test::phedra_cli({"check", tube, "--thickness-mm", "2", "--hinge", "pin", "--printer", "fdm"});
  CAPTURE(refused.err);
  CHECK(refused.code == 2);
  const std::string says = "--printer: fdm makes pin hinge parts for plates at least 5 mm thick (a pin 2 mm across is 0.4 T), "
                           "not 2 mm: --thickness-mm 5 on a scale of at least ";
  REQUIRE_THAT(refused.err, Contains(says));
  const std::string scale = refused.err.substr(refused.err.find(says) + says.size(), refused.err.find(" mm a model unit") -
                                                                                          refused.err.find(says) - says.size());
  CAPTURE(scale);
  // What it suggests works: those plates fit at t* on that scale, with pins the printer makes.
  const test::Run works = test::phedra_cli({"check", tube, "--thickness-mm", "5", "--hinge", "pin", "--printer", "fdm", "--scale", scale});
  CAPTURE(works.out, works.err);
  CHECK(works.code == 0);
  CHECK_THAT(works.out, Contains("pin hinges: "));
  // A printer of one's own, from a file; and every error of it.
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "phedra-printer";
  std::filesystem::create_directories(dir);
  auto file = [&](const std::string& name, const std::string& text) {
    std::ofstream((dir / name).string()) << text;
    return (dir / name).string();
  };
  const std::string mine = file("mine.json", R"({"pin_mm": 1.2, "gap_mm": 0.2, "clearance_mm": 0.2, "smallest_feature_mm": 0.5, "nozzle_mm": 0.25})");
  const test::Run own = test::phedra_cli({"check", tube, "--thickness-mm", "2", "--hinge", "pin", "--printer", mine});
  CHECK(own.code == 2);
  CHECK_THAT(own.err, Contains("makes pin hinge parts for plates at least 3 mm thick (a pin 1.2 mm across is 0.4 T)"));
  struct Refusal {
    std::vector<std::string> args;
    std::string says;
  };
  for (const Refusal& r : std::vector<Refusal>{
           {{"--thickness-mm", "5", "--printer", "fdm"}, "--printer: a printer sizes pin hinge parts: add --hinge pin"},
           {{"--thickness", "0.2", "--hinge", "pin", "--printer", "fdm"}, "--printer: a printer's sizes are millimetres: give --thickness-mm"},
           {{"--thickness-mm", "5", "--hinge", "pin", "--printer", "inkjet"}, "--printer: \"inkjet\" is neither fdm, sla nor a file"},
           {{"--thickness-mm", "5", "--hinge", "pin", "--printer", file("bad.json", "{")}, "bad.json: not JSON"},
           {{"--thickness-mm", "5", "--hinge", "pin", "--printer", file("list.json", "[1]")}, "list.json: expected an object of sizes in mm"},
           {{"--thickness-mm", "5", "--hinge", "pin", "--printer", file("key.json", R"({"pin": 2})")}, "key.json: unknown key \"pin\""},
           {{"--thickness-mm", "5", "--hinge", "pin", "--printer", file("neg.json", R"({"pin_mm": -2})")}, "neg.json: pin_mm must be a number of millimetres in (0, 100]"}}) {
    std::vector<std::string> args{"check", tube};
    args.insert(args.end(), r.args.begin(), r.args.end());
    const test::Run run = test::phedra_cli(args);
    CAPTURE(args, run.err);
    CHECK(run.code == 2);
    CHECK_THAT(run.err, Contains(r.says));
  }
  // generate sizes its parts so too: refused the same way, written on the scale that works.
  const std::string out = (dir / "pins.stl").string();
  CHECK(test::phedra_cli({"generate", tube, "--thickness-mm", "2", "--hinge", "pin", "--printer", "fdm", "-o", out}).code == 2);
  CHECK_FALSE(std::filesystem::exists(out));
  CHECK(test::phedra_cli({"generate", tube, "--thickness-mm", "5", "--hinge", "pin", "--printer", "fdm", "--scale", scale, "-o", out}).code == 0);
  CHECK(std::filesystem::exists(out));
  std::filesystem::remove_all(dir);
}
