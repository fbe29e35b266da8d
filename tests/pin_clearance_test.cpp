// Pin hinges that clear (issue 38, item 1): no two parts (plates, knuckles,
// pins) cut into each other at t* nor over the thick interval, by this test's
// own triangle-triangle crossing test over every pair of parts, a knuckle and
// the plate its leaf is glued to aside (they touch by design); printed in
// place, every two bodies the clearance apart, by the triangles' distance.

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
#include <limits>
#include <map>
#include <random>
#include <string>

using namespace phedra;
using Catch::Matchers::Contains;

namespace {

struct Crossing {
  std::string a, b;
  double depth = 0.0;
};

/// Every pair of solids that cut into each other (triangles crossing deeper
/// than `tolerance`), but a knuckle with its own plate: world-aligned boxes of
/// the solids, then of their triangles (each prepared once).
std::vector<Crossing> crossings(const std::vector<Solid>& solids, const std::vector<std::string>& names,
                                const std::vector<long>& own_plate, double tolerance) {
  struct Triangles {
    std::vector<PreparedTriangle> prepared;
    std::vector<Box> boxes;
  };
  std::vector<Box> boxes;
  std::vector<Triangles> triangles(solids.size());
  for (std::size_t k = 0; k < solids.size(); ++k) {
    const Solid& s = solids[k];
    Box b{s.vertices.front(), s.vertices.front()};
    for (const Vec3& v : s.vertices) b.lo = b.lo.cwiseMin(v), b.hi = b.hi.cwiseMax(v);
    boxes.push_back(b);
    for (const auto& t : s.triangles) {
      const Triangle tri{s.vertices[t[0]], s.vertices[t[1]], s.vertices[t[2]]};
      Box box{tri[0], tri[0]};
      for (const Vec3& c : tri) box.lo = box.lo.cwiseMin(c), box.hi = box.hi.cwiseMax(c);
      triangles[k].prepared.push_back(prepare(tri));
      triangles[k].boxes.push_back(box);
    }
  }
  std::vector<Crossing> out;
  std::vector<std::size_t> ti, tj;
  BoxTree(boxes).for_each_pair([&](std::size_t i, std::size_t j) {
    if (own_plate[i] == static_cast<long>(j) || own_plate[j] == static_cast<long>(i)) return true;
    // Each solid's triangles that reach into the other's box.
    auto near = [&](std::size_t a, std::size_t b, std::vector<std::size_t>& into) {
      into.clear();
      for (std::size_t k = 0; k < triangles[a].boxes.size(); ++k) {
        if (triangles[a].boxes[k].overlaps(boxes[b])) into.push_back(k);
      }
    };
    near(i, j, ti);
    near(j, i, tj);
    double deepest = 0.0;
    for (const std::size_t p : ti) {
      for (const std::size_t q : tj) {
        if (triangles[i].boxes[p].overlaps(triangles[j].boxes[q])) {
          deepest = std::max(deepest, triangle_penetration(triangles[i].prepared[p], triangles[j].prepared[q]));
        }
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
    const PinLayout layout = pin_layout(plates, pin_configurations(t_star, lower, upper, pin_layout_samples));
    // The check's judgement (`check --hinge pin`): no crossing at its configurations.
    const std::vector<double> checked = pin_configurations(t_star, lower, upper, 2 * pin_layout_samples - 1);
    CHECK(pin_crossings(plates, layout, checked).empty());
    // This test's own, at t*, the ends and half way between the check's
    // configurations in every other gap (where neither the layout nor the
    // check looked; all of them take twice the time and find none either).
    std::vector<double> ts{t_star, lower, upper};
    for (std::size_t k = 2; k < checked.size(); k += 2) ts.push_back(0.5 * (checked[k - 1] + checked[k]));
    for (const double t : ts) {
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

TEST_CASE("triangle_distance: the closest points of two triangles, against dense sampling of both", "[thick][pins]") {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  auto point = [&] { return Vec3(coordinate(random), coordinate(random), coordinate(random)); };
  // Points of a triangle on a barycentric grid (its corners, edges and inside).
  auto samples = [](const Triangle& t) {
    std::vector<Vec3> out;
    constexpr int n = 24;
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; i + j <= n; ++j) out.push_back(t[0] + (double(i) / n) * (t[1] - t[0]) + (double(j) / n) * (t[2] - t[0]));
    }
    return out;
  };
  int apart = 0, touching = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 shift = trial % 4 == 0 ? Vec3(Vec3::Zero()) : Vec3(2.0 * Vec3(coordinate(random), coordinate(random), coordinate(random)));
    Triangle p{point(), point(), point()};
    Triangle q{point() + shift, point() + shift, point() + shift};
    if (trial % 10 == 1) q = {p[0] + shift, p[1] + shift + Vec3(0.3, 0, 0), p[2] + shift};  // nearly parallel
    if (trial % 10 == 2) q = {p[1], p[0] + shift, p[2] + shift};                            // sharing a corner
    const double d = triangle_distance(prepare(p), prepare(q));
    double sampled = std::numeric_limits<double>::infinity();
    const std::vector<Vec3> sp = samples(p), sq = samples(q);
    for (const Vec3& a : sp) {
      for (const Vec3& b : sq) sampled = std::min(sampled, (a - b).norm());
    }
    CAPTURE(trial, d, sampled);
    // The exact distance is at most any sampled pair's, and the grid is fine enough to come close.
    CHECK(d <= sampled + 1e-12);
    CHECK(d >= 0.0);
    if (triangle_penetration(p, q) > 1e-12) {
      CHECK(d == 0.0);
      ++touching;
    } else {
      CHECK(d >= sampled - 0.08);
      apart += d > 0.0;
    }
  }
  CHECK(apart > 100);
  CHECK(touching > 5);
}

TEST_CASE("pin hinges printed in place: a body a plate, every part of one the pin's play from every part of another", "[thick][pins]") {
  const Design design = load_design(test::presets + "/parallelogram-tube.json");
  const double size = design.assembly.model_size();
  ThickOptions options;
  options.thickness = 0.01 * size;
  options.hinge_gap = pin_hinge_gap(options.thickness);
  const ThickReport report = check_thickness(design, assess_buildability(design), options);
  const ThickPlates plates = thick_plates(design, report);
  const double t = report.t_star, clearance = in_place_clearance(options.thickness);
  CHECK(clearance == Approx(0.05 * options.thickness));
  // The layout generate makes (under the sanitizers, at t alone: the in-place search is the same, 10 times cheaper).
#ifdef PHEDRA_SANITIZE_BUILD
  const std::vector<double> ts{t};
#else
  const std::vector<double> ts = pin_configurations(t, report.thick_lower, report.thick_upper, pin_layout_samples);
#endif
  const PinLayout layout = pin_layout(plates, ts, InPlace{t, clearance});
  REQUIRE(layout.in_place);
  const Points x = plates.positions(t);
  const HingeParts parts = pin_hinge_parts(plates, x, layout);
  REQUIRE(parts.body.size() == parts.solids.size());
  CHECK(pin_gaps(plates, layout, t, clearance).empty());
  // This test's own measure: every two solids of different bodies (plates,
  // knuckles, pins; one hinge's own parts too: the design's clearances) at
  // least the clearance apart, by the triangles' distance.
  std::vector<Solid> solids = plates.solids(x);
  std::vector<std::size_t> body;
  for (std::size_t k = 0; k < plates.plates(); ++k) body.push_back(plates.panel(k));
  for (std::size_t k = 0; k < parts.solids.size(); ++k) {
    solids.push_back(parts.solids[k]);
    body.push_back(parts.body[k]);
    // A knuckle moves with its own plate (named first), a pin with the first plate of its hinge.
    const std::string& name = parts.names[k];
    CHECK(std::to_string(parts.body[k]) == name.substr(name.find('_') + 1, name.find('_', name.find('_') + 1) - name.find('_') - 1));
  }
  // Each solid's triangles with their boxes grown by the clearance (two
  // triangles nearer than it have overlapping grown boxes).
  std::vector<Box> boxes;
  std::vector<std::vector<std::pair<PreparedTriangle, Box>>> triangles(solids.size());
  auto grown = [&](Box b) { return Box{(b.lo.array() - 0.5 * clearance).matrix(), (b.hi.array() + 0.5 * clearance).matrix()}; };
  for (std::size_t k = 0; k < solids.size(); ++k) {
    Box b{solids[k].vertices.front(), solids[k].vertices.front()};
    for (const Vec3& v : solids[k].vertices) b.lo = b.lo.cwiseMin(v), b.hi = b.hi.cwiseMax(v);
    boxes.push_back(grown(b));
    for (const auto& tri : solids[k].triangles) {
      const Triangle corners{solids[k].vertices[tri[0]], solids[k].vertices[tri[1]], solids[k].vertices[tri[2]]};
      Box tb{corners[0], corners[0]};
      for (const Vec3& c : corners) tb.lo = tb.lo.cwiseMin(c), tb.hi = tb.hi.cwiseMax(c);
      triangles[k].push_back({prepare(corners), grown(tb)});
    }
  }
  double nearest = std::numeric_limits<double>::infinity();
  std::size_t pairs = 0;
  BoxTree(boxes).for_each_pair([&](std::size_t i, std::size_t j) {
    if (body[i] == body[j]) return true;
    ++pairs;
    for (const auto& [p, bp] : triangles[i]) {
      if (!bp.overlaps(boxes[j])) continue;
      for (const auto& [q, bq] : triangles[j]) {
        if (bp.overlaps(bq)) nearest = std::min(nearest, triangle_distance(p, q));
      }
    }
    return true;
  });
  CAPTURE(pairs, nearest / options.thickness);
  CHECK(pairs > 100);
  CHECK(nearest >= clearance * (1.0 - 1e-9));
  CHECK(nearest <= clearance * 1.05);  // the pin in the knuckles turning on it: the play, as designed
  // The bodies: a plate each, with every part that moves with it.
  const InPlaceBodies bodies = in_place_bodies(plates, plates.solids(x), parts);
  REQUIRE(bodies.solids.size() == plates.plates());
  std::size_t shells = 0;
  for (const std::size_t n : bodies.shells) shells += n;
  CHECK(shells == plates.plates() + parts.solids.size());
  CHECK(bodies.names.front() == "body_" + std::to_string(plates.panel(0)));
}

TEST_CASE("generate --print-in-place: the bodies in one object, and every refusal", "[thick][pins][cli]") {
  test::TempDir dir("in-place");
  const std::string tube = test::presets + "/parallelogram-tube.json";
  const std::string out = (dir.path / "tube.3mf").string();
  const test::Run run = test::phedra_cli({"generate", tube, "--thickness-mm", "1.5", "--model-size", "150", "--hinge", "pin",
                                          "--print-in-place", "-o", out});
  CAPTURE(run.out, run.err);
  REQUIRE(run.code == 0);
  CHECK_THAT(run.out, Contains("printed in place: 40 bodies"));
  CHECK_THAT(run.out, Contains("at least 0.075 mm from every part of another at t = 1"));
  // 0.075 mm is under what an FDM printer keeps open: said.
  CHECK_THAT(run.err, Contains("phedra: warning: parts printed in place 0.075 mm apart fuse on an FDM printer (it needs 0.3 mm"));
  // One object: a slicer places the bodies as a whole (PrusaSlicer reads it in
  // tests/prusa/check_print_beds.sh). A 3MF's entries are stored: its model is plain in it.
  std::ifstream in(out, std::ios::binary);
  const std::string model((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto count_of = [&](const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
  };
  CHECK(count_of(model, "<object ") == 1);
  CHECK(count_of(model, "<item ") == 1);
  struct Refusal {
    std::vector<std::string> args;
    std::string says;
  };
  const std::string fused = (dir.path / "fused.3mf").string();
  for (const Refusal& r : std::vector<Refusal>{
           {{"--thickness-mm", "1.5", "--print-in-place", "-o", out}, "--print-in-place: parts printed in place turn on pins: add --hinge pin"},
           {{"--hinge", "pin", "--print-in-place", "-o", (dir.path / "a.glb").string()}, "--print-in-place: parts printed in place are solids"},
           {{"--thickness-mm", "1.5", "--hinge", "pin", "--print-in-place", "--layout", "print", "-o", out},
            "--print-in-place: parts printed in place are printed assembled; --layout print lays them apart: choose one"},
           {{"--thickness-mm", "5", "--model-size", "150", "--hinge", "pin", "--print-in-place", "--printer", "fdm", "-o", out},
            "--printer: fdm makes pin hinge parts printed in place for plates at least 6 mm thick (a pin's play of 0.3 mm in its hole, printed in place, is 0.05 T)"},
           // At the thick interval's end two plates touch: they would print fused.
           {{"--thickness", "0.0853", "--hinge", "pin", "--print-in-place", "--at", "1.3388", "-o", fused},
            "of parts of different bodies closer than the clearance 0.004265 model units at t = 1.3388 (they would print fused): the nearest plate_"}}) {
    std::vector<std::string> args{"generate", tube};
    args.insert(args.end(), r.args.begin(), r.args.end());
    const test::Run refused = test::phedra_cli(args);
    CAPTURE(args, refused.err);
    CHECK(refused.code == 2);
    CHECK_THAT(refused.err, Contains(r.says));
  }
  CHECK_FALSE(std::filesystem::exists(fused));
}
