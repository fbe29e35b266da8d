// Thick panels (issue 27): plates offset to one side, bevelled at the hinges.
// Every solid closed and outward; the thick interval verified by an independent
// collision test of the solids' triangles (not the SAT of the check); errors.

#include "phedra/box_tree.h"
#include "phedra/buildability.h"
#include "phedra/cut_sheets.h"
#include "phedra/sheet_geometry.h"
#include "support/cli_run.h"
#include "phedra/errors.h"
#include "phedra/design_preset.h"
#include "phedra/solid_export.h"
#include "phedra/thick_plates.h"
#include "phedra/hinge_pins.h"
#include "phedra/number_format.h"
#include "phedra/triangle_overlap.h"
#include "support/random_input.h"
#include "support/test_files.h"

#include <catch2/catch.hpp>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <cstdio>
#include <sstream>

using namespace phedra;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

using test::presets;

#ifdef PHEDRA_SANITIZE_BUILD  // the code paths there (10x slower); the sizes in the Release run
constexpr bool sanitized = true;
constexpr std::size_t inside_samples = 3;
constexpr int random_designs = 3;
#else
constexpr bool sanitized = false;
constexpr std::size_t inside_samples = 24;
constexpr int random_designs = 8;
#endif

/// Every directed edge of the solid appears once and its reverse once: closed and consistently oriented.
bool closed_and_oriented(const Solid& s) {
  std::map<std::pair<std::size_t, std::size_t>, int> edges;
  for (const auto& t : s.triangles) {
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  }
  for (const auto& [edge, count] : edges) {
    if (count != 1) return false;
    const auto back = edges.find({edge.second, edge.first});
    if (back == edges.end() || back->second != 1) return false;
  }
  return true;
}

Box box_of(const Solid& s) {
  Box b{s.vertices.front(), s.vertices.front()};
  for (const Vec3& v : s.vertices) {
    b.lo = b.lo.cwiseMin(v);
    b.hi = b.hi.cwiseMax(v);
  }
  return b;
}

/// The deepest crossing of any two solids' triangles at x (independent of the
/// check's convex pieces and SAT), with the pair.
struct Deepest {
  double depth = -1.0;
  std::size_t a = 0, b = 0;
};
Deepest deepest_crossing(const std::vector<Solid>& solids) {
  Deepest d;
  std::vector<Box> boxes;
  for (const Solid& s : solids) boxes.push_back(box_of(s));
  for (std::size_t i = 0; i < solids.size(); ++i) {
    for (std::size_t j = i + 1; j < solids.size(); ++j) {
      if (!boxes[i].overlaps(boxes[j])) continue;
      for (const auto& p : solids[i].triangles) {
        const Triangle tp{solids[i].vertices[p[0]], solids[i].vertices[p[1]], solids[i].vertices[p[2]]};
        for (const auto& q : solids[j].triangles) {
          const Triangle tq{solids[j].vertices[q[0]], solids[j].vertices[q[1]], solids[j].vertices[q[2]]};
          const double depth = triangle_penetration(tp, tq);
          if (depth > d.depth) d = {depth, i, j};
        }
      }
    }
  }
  return d;
}

std::vector<std::string> buildable_presets() {
  std::vector<std::string> out;
  for (const auto& entry : fs::directory_iterator(presets)) {
    const std::string name = entry.path().filename().string();
    // (under the sanitizers: the three small ones)
    const bool small = name == "default.json" || name == "parallelogram-tube.json" || name == "helix-tube.json";
    if (entry.path().extension() == ".json" && name != "preset.schema.json" && name.rfind("anti-parallelogram", 0) != 0 &&
        (small || !sanitized)) {
      out.push_back(entry.path().string());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// The solids' properties and the thick interval's verification for one design at thickness T.
void verify(const Design& design, double thickness, std::size_t samples) {
  const BuildabilityReport thin = assess_buildability(design);
  ThickOptions options;
  options.thickness = thickness;
  const ThickReport report = check_thickness(design, thin, options);
  const ThickPlates plates = thick_plates(design, report);
  const double size = design.assembly.model_size();
  // Closed, outward solids; volume close to T x area.
  const std::vector<Solid> at_star = plates.solids(plates.positions(report.t_star));
  double volume = 0.0;
  for (const Solid& s : at_star) {
    REQUIRE(closed_and_oriented(s));
    REQUIRE(s.volume() > 0.0);
    volume += s.volume();
  }
  CHECK(volume == Approx(report.volume).epsilon(1e-9));
  CHECK(volume <= thickness * report.panel_area * (1.0 + 1e-9));
  CHECK(volume >= 0.8 * thickness * report.panel_area);  // bevels and floors take at most a fifth
  if (report.at_t_star) return;
  // Inside the thick interval no two solids cross; just past a plates limit some do.
  for (std::size_t k = 0; k <= samples; ++k) {
    const double t = report.thick_lower + (report.thick_upper - report.thick_lower) * static_cast<double>(k) / static_cast<double>(samples);
    const Deepest d = deepest_crossing(plates.solids(plates.positions(t)));
    INFO(design.assembly.name() << " at t = " << t << ": plates " << d.a << ", " << d.b << " cross by " << d.depth);
    REQUIRE(d.depth <= 1e-7 * size);
  }
  const double width = report.t_mu - report.t_lambda;
  for (const auto& [limit, sign] : {std::pair{report.lower, -1.0}, std::pair{report.upper, 1.0}}) {
    if (!limit || limit->kind == ThickLimit::Kind::thin) continue;
    const double end = sign < 0 ? report.bevel_lower : report.bevel_upper;
    const double t = limit->t + sign * std::min(0.01 * width, 0.5 * std::abs(end - limit->t));
    const Deepest d = deepest_crossing(plates.solids(plates.positions(t)));
    INFO(design.assembly.name() << " past the thick limit " << limit->t << ", at " << t);
    CHECK(d.depth > 0.0);
  }
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("thick plates: every shipped preset at 1 % of its size: closed solids, the thick interval verified", "[thick]") {
  for (const std::string& path : buildable_presets()) {
    INFO(path);
    const Design design = load_design(path);
    verify(design, 0.01 * design.assembly.model_size(), inside_samples);
  }
}

TEST_CASE("thick plates: random buildable open designs", "[thick]") {
  // Random designs are mostly not buildable at t* (bow-ties): draw until enough are.
  std::mt19937_64 rng(2027);
  int redrawn = 0, checked = 0, misfits = 0, attempts = 0;
  for (; attempts < 2000 && checked + misfits < random_designs; ++attempts) {
    test::RandomInputShape shape;
    shape.strips = 3 + attempts % 4;
    shape.profile_vertices = 3 + attempts % 3;
    shape.smooth = true;
    const std::optional<PHedron> p = test::draw_phedron([&] { return test::random_input(rng, shape); }, redrawn);
    REQUIRE(p);
    const Design design = single_design(p->input());
    BuildabilityOptions quick;
    quick.sweep_motion = false;
    if (!assess_buildability(design, nullptr, quick).interval()) continue;
    if (!assess_buildability(design).interval()) continue;
    INFO("attempt " << attempts);
    try {
      verify(design, 0.01 * design.assembly.model_size(), inside_samples / 2);
      ++checked;
    } catch (const InvalidInputError& e) {
      CHECK_THAT(std::string(e.what()), Contains("does not fit on panel"));  // a sliver panel: said, not built
      ++misfits;
    }
  }
  WARN("thick plates on random designs: " << checked << " verified, " << misfits << " too thin a panel, "
                                          << attempts << " drawn");
  CHECK(checked >= random_designs - 2);
}

TEST_CASE("thick plates: the bevels follow the plate-side opening, and the motion is the panels'", "[thick]") {
  const Design design = load_design(presets + "/parallelogram-tube.json");
  const BuildabilityReport thin = assess_buildability(design);
  for (const PlateSide side : {PlateSide::front, PlateSide::back}) {
    ThickOptions options;
    options.thickness = 0.05;
    options.side = side;
    const ThickReport report = check_thickness(design, thin, options);
    CHECK(report.side == side);
    const ThickPlates plates = thick_plates(design, report);
    // Each plate's bottom face is its panel at every t (hinges on the fold lines).
    const AssemblyMesh& mesh = plates.mesh();
    for (const double t : {report.thick_lower, report.t_star, report.thick_upper}) {
      const Points x = plates.positions(t);
      const std::vector<Solid> solids = plates.solids(x);
      for (std::size_t k = 0; k < plates.plates(); ++k) {
        const Quad& q = mesh.faces[plates.panel(k)];
        for (int c = 0; c < 4; ++c) {
          const double nearest = (solids[k].vertices[0] - x[q[c]]).norm();
          double best = nearest;
          for (const Vec3& v : solids[k].vertices) best = std::min(best, (v - x[q[c]]).norm());
          CHECK(best < 1e-9 * design.assembly.model_size());
        }
      }
    }
  }
}

TEST_CASE("thick plates: a hinge gap moves each plate back from its hinges by half of it", "[thick]") {
  const Design design = load_design(presets + "/parallelogram-tube.json");
  const BuildabilityReport thin = assess_buildability(design);
  ThickOptions options;
  options.thickness = 0.08;
  const ThickReport plain = check_thickness(design, thin, options);
  options.hinge_gap = 0.05;
  const ThickReport gapped = check_thickness(design, thin, options);
  CHECK(gapped.hinge_gap == 0.05);
  CHECK(gapped.volume < plain.volume);
  const ThickPlates plates = thick_plates(design, gapped);
  const ThickPlates whole = thick_plates(design, plain);
  const Points x = plates.positions(gapped.t_star);
  const std::vector<Solid> solids = plates.solids(x);
  // The mesh's edges with two panels are the hinges: every bottom corner of a
  // plate keeps half the gap from each hinge line of its panel.
  std::map<std::pair<std::size_t, std::size_t>, int> uses;
  for (std::size_t k = 0; k < plates.plates(); ++k) {
    const Quad& q = plates.mesh().faces[plates.panel(k)];
    for (int c = 0; c < 4; ++c) ++uses[{std::min(q[c], q[(c + 1) % 4]), std::max(q[c], q[(c + 1) % 4])}];
  }
  std::size_t hinge_sides = 0;
  for (std::size_t k = 0; k < plates.plates(); ++k) {
    REQUIRE(closed_and_oriented(solids[k]));
    const Quad& q = plates.mesh().faces[plates.panel(k)];
    for (int c = 0; c < 4; ++c) {
      const std::size_t u = q[c], v = q[(c + 1) % 4];
      if (uses[{std::min(u, v), std::max(u, v)}] < 2) continue;
      ++hinge_sides;
      const Vec3 a = x[u], d = (x[v] - x[u]).normalized();
      for (std::size_t b = 0; b < plates.bottom(k).size(); ++b) {
        const Vec3& p = solids[k].vertices[b];
        CHECK(((p - a) - (p - a).dot(d) * d).norm() >= 0.025 - 1e-9);
      }
    }
  }
  CHECK(hinge_sides == 2 * 76);  // 76 hinges, two plates each
  CHECK(whole.bottom(0).size() == plates.bottom(0).size());
  const test::Run big = test::phedra_cli({"check", presets + "/parallelogram-tube.json", "--thickness", "0.08", "--hinge-gap", "5"});
  CHECK(big.code == 2);
  CHECK_THAT(big.err, Contains("--hinge-gap: a hinge gap of 5 leaves nothing of panel"));
}

TEST_CASE("thick plates: pin hinges: knuckles on the hinge lines, alternating, clear of the other plate, pins", "[thick]") {
  const Design design = load_design(presets + "/parallelogram-tube.json");
  const BuildabilityReport thin = assess_buildability(design);
  ThickOptions options;
  options.thickness = 0.08;
  options.hinge_gap = pin_hinge_gap(options.thickness);
  const ThickReport report = check_thickness(design, thin, options);
  const ThickPlates plates = thick_plates(design, report);
  const Points x = plates.positions(report.t_star);
  // The layout generate makes at t*: clear at t* and the thick interval's ends (tests/pin_clearance_test.cpp).
  const PinLayout layout = pin_layout(plates, {report.t_star, report.thick_lower, report.thick_upper});
  const HingeParts parts = pin_hinge_parts(plates, x, layout);
  const PinSizes sizes(options.thickness);
  CHECK(parts.hinges + layout.without_knuckles == 76);
  CHECK(parts.hinges >= 60);
  CHECK(parts.pins == parts.hinges);
  CHECK(parts.knuckles >= 3 * parts.hinges);
  REQUIRE(parts.solids.size() == parts.knuckles + parts.pins);
  REQUIRE(parts.names.size() == parts.solids.size());
  // Every part closed, outward (positive volume) and of the volume of its profile times its length.
  const double disc = M_PI * (sizes.knuckle_radius * sizes.knuckle_radius - sizes.hole_radius * sizes.hole_radius);
  const double leaf = sizes.leaf_thickness * (sizes.leaf_reach - std::sqrt(sizes.knuckle_radius * sizes.knuckle_radius -
                                                                         sizes.leaf_thickness * sizes.leaf_thickness));
  // Hinge lines: the mesh edges with two plates.
  std::map<std::pair<std::size_t, std::size_t>, std::vector<std::size_t>> sides;
  for (std::size_t k = 0; k < plates.plates(); ++k) {
    const Quad& q = plates.mesh().faces[plates.panel(k)];
    for (int c = 0; c < 4; ++c) sides[{std::min(q[c], q[(c + 1) % 4]), std::max(q[c], q[(c + 1) % 4])}].push_back(plates.panel(k));
  }
  std::map<std::string, std::vector<std::pair<double, double>>> along;  // a hinge's knuckles: their spans on its line
  for (std::size_t k = 0; k < parts.solids.size(); ++k) {
    const Solid& s = parts.solids[k];
    INFO(parts.names[k]);
    REQUIRE(closed_and_oriented(s));
    CHECK(s.volume() > 0.0);
    // The part's hinge: the line its vertices lie closest to (pins: all within the pin radius of it).
    const bool is_pin = parts.names[k].rfind("pin_", 0) == 0;
    std::optional<std::pair<Vec3, Vec3>> line;
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& [edge, faces] : sides) {
      if (faces.size() != 2) continue;
      const Vec3 a = x[edge.first], d = (x[edge.second] - x[edge.first]).normalized();
      double worst = 0.0;
      for (std::size_t v = 0; v < (is_pin ? s.vertices.size() : 2 * 33); ++v) {  // a knuckle's first 33: its outer arc
        const Vec3 p = s.vertices[v < 33 || is_pin ? v : v - 33 + s.vertices.size() / 2];
        worst = std::max(worst, ((p - a) - (p - a).dot(d) * d).norm());
      }
      if (worst < nearest) nearest = worst, line = {a, d};
    }
    REQUIRE(line);
    const double radius = is_pin ? sizes.pin_radius : sizes.knuckle_radius;
    CHECK(nearest == Approx(radius).epsilon(1e-9));  // on the hinge line: the pin's axis, the knuckle's tube
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Vec3& p : s.vertices) lo = std::min(lo, (p - line->first).dot(line->second)), hi = std::max(hi, (p - line->first).dot(line->second));
    const double length = hi - lo;
    CHECK(s.volume() == Approx((is_pin ? M_PI * radius * radius * 0.9886 : disc + leaf) * length).epsilon(0.04));
    if (!is_pin) along[parts.names[k].substr(0, parts.names[k].rfind('_'))].push_back({lo, hi});
  }
  // Along each hinge its knuckles alternate between its two plates and keep the clearance between them.
  std::map<std::pair<std::size_t, std::size_t>, std::vector<std::pair<double, double>>> per_hinge;
  for (const auto& [name, spans] : along) {
    const std::size_t a = std::stoul(name.substr(8, name.find('_', 8) - 8)), b = std::stoul(name.substr(name.find('_', 8) + 1));
    auto& all = per_hinge[{std::min(a, b), std::max(a, b)}];
    all.insert(all.end(), spans.begin(), spans.end());
  }
  CHECK(per_hinge.size() == parts.hinges);
  for (auto& [hinge, spans] : per_hinge) {
    std::sort(spans.begin(), spans.end());
    CHECK(spans.size() % 2 == 1);
    for (std::size_t k = 1; k < spans.size(); ++k) CHECK(spans[k].first - spans[k - 1].second >= sizes.clearance - 1e-9);
  }
  // The plates are cut back so that a knuckle turning about the hinge line clears them.
  CHECK(0.5 * report.hinge_gap >= sizes.knuckle_radius + sizes.clearance - 1e-12);
  const std::string out = (std::filesystem::temp_directory_path() / "phedra-pins.stl").string();
#ifndef PHEDRA_SANITIZE_BUILD  // the command's words (each command runs the layout search again: 20 s there); the library's above
  // The command: pins after the plates, named in the file.
  const test::Run run = test::phedra_cli({"generate", presets + "/parallelogram-tube.json", "--thickness", "0.08", "--hinge", "pin", "-o", out});
  CHECK(run.code == 0);
  CHECK_THAT(run.out, Contains("wrote " + out + ": 40 plates"));
  CHECK_THAT(run.out, Contains("pin hinges: " + std::to_string(parts.hinges) + " hinges, " + std::to_string(parts.knuckles) + " knuckles"));
  CHECK_THAT(run.out, Contains(std::to_string(parts.pins) + " pins"));
  if (layout.without_knuckles > 0) {
    CHECK_THAT(run.out, Contains(std::to_string(layout.without_knuckles) + (layout.without_knuckles == 1 ? " hinge" : " hinges") +
                                 " left without knuckles"));
  }
  // check --hinge pin says the same layout: how many hinges keep their knuckles (text and JSON).
  const test::Run said = test::phedra_cli({"check", presets + "/parallelogram-tube.json", "--thickness", "0.08", "--hinge", "pin"});
  CHECK(said.code == 0);
  CHECK_THAT(said.out, Contains("pin hinges: " + std::to_string(parts.hinges) + " of 76 hinges keep knuckles clear of each other"));
  const test::Run as_json = test::phedra_cli({"check", presets + "/parallelogram-tube.json", "--thickness", "0.08", "--hinge", "pin", "--json"});
  REQUIRE(as_json.code == 0);
  const nlohmann::json pin_hinges = nlohmann::json::parse(as_json.out)["thick"]["pin_hinges"];
  CHECK(pin_hinges["hinges"] == 76);
  CHECK(pin_hinges["with_knuckles"] == parts.hinges);
  CHECK(pin_hinges["without_knuckles"] == layout.without_knuckles);
  std::filesystem::remove(out);
#endif
  const test::Run bad = test::phedra_cli({"generate", presets + "/parallelogram-tube.json", "--thickness", "0.08", "--hinge", "rivet", "-o", out});
  CHECK(bad.code == 2);
  CHECK_THAT(bad.err, Contains("--hinge"));
  CHECK_FALSE(std::filesystem::exists(out));
}

TEST_CASE("thick plates: plates that meet at one corner only are cut back there until they clear", "[thick]") {
  // edge-sharing-pair: the two tubes' plates meet at the shared edge's ends
  // (no hinge between them); at 1 % of the size they overlapped at t*.
  const Design design = load_design(presets + "/edge-sharing-pair.json");
  const BuildabilityReport thin = assess_buildability(design);
  ThickOptions options;
  options.thickness = 0.01 * design.assembly.model_size();
  const ThickReport report = check_thickness(design, thin, options);
  CHECK_FALSE(report.at_t_star);
  CHECK(report.thick_lower <= report.t_star);
  CHECK(report.thick_upper > report.t_star);
  const ThickPlates plates = thick_plates(design, report);
  CHECK(plates.corners_trimmed() > 0);
  const std::vector<Solid> solids = plates.solids(plates.positions(report.t_star));
  std::size_t cut = 0;
  for (std::size_t k = 0; k < plates.plates(); ++k) {
    REQUIRE(closed_and_oriented(solids[k]));
    CHECK(solids[k].volume() > 0.0);
    if (plates.bottom(k).size() > plates.panel_corners(k).size()) {
      ++cut;
      // A cut corner: the top keeps as many corners as the bottom, every one inside the panel's bottom face's plane side.
      CHECK(plates.top(k).size() == plates.bottom(k).size());
    }
  }
  CHECK(cut > 0);
  CHECK(cut <= plates.corners_trimmed());
}

TEST_CASE("thick plates: the thickest plates that fit at t*", "[thick]") {
  for (const std::string name : {"default", sanitized ? "parallelogram-tube" : "grid-3x3"}) {
    INFO(name);
    const Design design = load_design(presets + "/" + name + ".json");
    const BuildabilityReport thin = assess_buildability(design);
    ThickOptions options;
    options.thickness = 0.001 * design.assembly.model_size();
    options.side = PlateSide::back;
    options.find_thickest = true;
    const ThickReport r = check_thickness(design, thin, options);
    REQUIRE(r.thickest);
    REQUIRE(*r.thickest > 0.0);
    auto collides_at_t_star = [&](double thickness) {
      ThickOptions o = options;
      o.thickness = thickness;
      o.find_thickest = false;
      try {
        return !check_thickness(design, thin, o).collision_free_at_t_star();
      } catch (const InvalidInputError&) {
        return true;  // a plate's top face vanishes: it does not fit either
      }
    };
    CHECK_FALSE(collides_at_t_star(*r.thickest));
    CHECK(collides_at_t_star(1.05 * *r.thickest));
  }
}

TEST_CASE("thick plates: the thickest that fit, the same whatever thickness check ran at, with every hinge mode and unit", "[thick][cli]") {
  // A pin hinge's gap grows with the plates (1.16 T), a default gap too (T / 4):
  // the search gives each thickness its own. At the figure the plates fit, 5 % over not.
  struct Case {
    std::string preset, hinge;
  };
  const std::vector<Case> cases = sanitized ? std::vector<Case>{{"default", "pin"}}
                                            : std::vector<Case>{{"default", "none"}, {"default", "pin"}, {"parallelogram-tube", "gap"}};
  for (const Case& c : cases) {
    CAPTURE(c.preset, c.hinge);
    const std::string path = presets + "/" + c.preset + ".json";
    auto check = [&](const std::vector<std::string>& extra) {
      std::vector<std::string> args{"check", path, "--hinge", c.hinge, "--json"};
      args.insert(args.end(), extra.begin(), extra.end());
      return test::phedra_cli(args);
    };
    const test::Run thin = check({"--thickness", "0.01"}), thick = check({"--thickness", "0.04"});
    REQUIRE(thin.code == 0);
    REQUIRE(thick.code == 0);
    const nlohmann::json a = nlohmann::json::parse(thin.out)["thick"], b = nlohmann::json::parse(thick.out)["thick"];
    const double thickest = a["thickest_at_t_star"].get<double>();
    REQUIRE(thickest > 0.0);
    CHECK(b["thickest_at_t_star"].get<double>() == thickest);
    CHECK(b["thickest_side"] == a["thickest_side"]);
    const std::string side = a["thickest_side"].get<std::string>();
    CHECK(check({"--thickness", format_number(thickest), "--plate-side", side}).code == 0);
    const test::Run over = check({"--thickness", format_number(1.05 * thickest), "--plate-side", side});
    CHECK(over.code != 0);
    CHECK(over.code != 4);
    // In millimetres with --thickness-mm: the same figure on the sheets' scale.
    const nlohmann::json mm = nlohmann::json::parse(check({"--thickness-mm", "1"}).out)["thick"];
    CHECK(mm["thickest_at_t_star"].get<double>() == thickest);
    CHECK(mm["thickest_at_t_star_mm"].get<double>() == Approx(thickest * mm["millimetres_per_unit"].get<double>()).epsilon(1e-12));
  }
}

TEST_CASE("thick plates on cut sheets that hardly fold: said in words on the first page and by the command, with a thickness that folds", "[thick][cli]") {
  test::TempDir dir("thick");
  const std::string preset = presets + "/all-plus.json";
  const test::Run thick = test::phedra_cli({"outlines", preset, "--thickness-mm", "6.5", "-o", (dir.path / "a.svg").string()});
  REQUIRE(thick.code == 0);
  CHECK_THAT(thick.err, Contains("phedra: warning: these 6.5 mm plates cannot fold: they collide at t*"));
  const std::string page = read_file(dir.path / "a-1.svg");
  CHECK_THAT(page, Contains("these 6.5 mm plates cannot fold: they collide at t*"));
  const std::size_t at = thick.err.find("fold over half of it (--thickness-mm ");
  REQUIRE(at != std::string::npos);
  std::istringstream suggested(thick.err.substr(at + std::string("fold over half of it (--thickness-mm ").size()));
  std::string mm, flag, side;
  suggested >> mm >> flag >> side;
  side.erase(side.find(')'));
  CHECK(flag == "--plate-side");
  CHECK_THAT(page, Contains("plates up to " + mm + " mm thick on the " + side + " side fold over half of it"));
  // As suggested: no warning, and they move over half the flexion interval.
  const test::Run thin = test::phedra_cli({"outlines", preset, "--thickness-mm", mm, "--plate-side", side, "-o", (dir.path / "b.svg").string()});
  REQUIRE(thin.code == 0);
  CHECK(thin.err.find("cannot fold") == std::string::npos);
  const std::size_t i = thin.out.find("thick interval [");
  REQUIRE(i != std::string::npos);
  double a = 0, b = 0, c = 0, d = 0;
  REQUIRE(std::sscanf(thin.out.c_str() + i, "thick interval [%lf, %lf] of [%lf, %lf]", &a, &b, &c, &d) == 4);
  CHECK((b - a) >= 0.5 * (d - c) * (1.0 - 1e-6));
  // Plates that fold over most of it say nothing of the kind.
  CHECK(test::phedra_cli({"outlines", preset, "--thickness-mm", "1", "-o", (dir.path / "c.svg").string()}).err.find("fold") == std::string::npos);
}

TEST_CASE("thick plates: check --thickness reports the thick interval, and plates colliding at t* fail, named", "[thick][cli]") {
  std::ostringstream out, err;
  REQUIRE(cli::run({"check", presets + "/parallelogram-tube.json", "--thickness", "0.08", "--json"}, out, err) == 0);
  const nlohmann::json j = nlohmann::json::parse(out.str());
  REQUIRE(j["thick_interval"].is_array());
  CHECK(j["thick"]["plates"] == 40);
  CHECK(j["thick"]["side"] == "front");
  CHECK(j["passed"] == true);
  CHECK(j["thick"]["thickest_at_t_star"].get<double>() > 0.08);
  if (!sanitized) {  // (the grid's sweep: the Release run's)
    std::ostringstream out2, err2;
    // (0.08 collided at t* before plates meeting at one corner were cut back there; 0.14 still does.)
    CHECK(cli::run({"check", presets + "/grid-3x3.json", "--thickness", "0.14"}, out2, err2) == 1);
    CHECK_THAT(out2.str(), Contains("FAIL: the plates 0.14 thick collide at t*"));
    CHECK_THAT(out2.str(), Contains("panel "));
  }
  std::ostringstream out3, err3;
  CHECK(cli::run({"check", presets + "/default.json", "--thickness", "0.1", "--plate-side", "front"}, out3, err3) == 0);
  CHECK_THAT(out3.str(), Contains("thick interval ["));
}

TEST_CASE("thick plates: generate writes STL, 3MF and OBJ solids", "[thick][cli]") {
  test::TempDir dir("thick");
  const std::string tube = presets + "/parallelogram-tube.json";
  std::ostringstream out, err;
  REQUIRE(cli::run({"generate", tube, "--thickness", "0.08", "-o", (dir.path / "t.stl").string()}, out, err) == 0);
  const std::string stl = read_file(dir.path / "t.stl");
  REQUIRE(stl.size() > 84);
  std::uint32_t count = 0;
  std::memcpy(&count, stl.data() + 80, 4);
  CHECK(count == 40 * 12);
  CHECK(stl.size() == 84 + 50 * static_cast<std::size_t>(count));
  CHECK(stl.rfind("solid", 0) != 0);
  // 3MF: a zip whose model lists every plate; the stored CRCs hold.
  REQUIRE(cli::run({"generate", tube, "--thickness", "0.08", "-o", (dir.path / "t.3mf").string()}, out, err) == 0);
  const std::string zip = read_file(dir.path / "t.3mf");
  std::size_t at = 0, entries = 0;
  bool model = false;
  while (at + 30 <= zip.size() && zip.compare(at, 4, "PK\x03\x04") == 0) {
    std::uint32_t crc = 0, size = 0;
    std::uint16_t name_length = 0, extra = 0;
    std::memcpy(&crc, zip.data() + at + 14, 4);
    std::memcpy(&size, zip.data() + at + 18, 4);
    std::memcpy(&name_length, zip.data() + at + 26, 2);
    std::memcpy(&extra, zip.data() + at + 28, 2);
    const std::string name = zip.substr(at + 30, name_length);
    const std::string bytes = zip.substr(at + 30 + name_length + extra, size);
    CHECK(crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size())) == crc);
    if (name == "3D/3dmodel.model") {
      model = true;
      std::size_t objects = 0;
      for (std::size_t p = bytes.find("<object "); p != std::string::npos; p = bytes.find("<object ", p + 1)) ++objects;
      CHECK(objects == 40);
      CHECK_THAT(bytes, Contains("name=\"plate_0\""));
    }
    ++entries;
    at += 30 + name_length + extra + size;
  }
  CHECK(entries == 3);
  CHECK(model);
  REQUIRE(cli::run({"generate", tube, "--thickness", "0.08", "-o", (dir.path / "t.obj").string()}, out, err) == 0);
  const std::string obj = read_file(dir.path / "t.obj");
  CHECK_THAT(obj, Contains("o plate_39"));
}

TEST_CASE("thick plates: --thickness-mm solids in millimetres, on the cut sheets' scale", "[thick][cli]") {
  test::TempDir dir("thick");
  const std::string tube = presets + "/parallelogram-tube.json";
  // The scale the sheets use, and the one generate says.
  const auto number_after = [](const std::string& text, const std::string& before) {
    const std::size_t at = text.find(before);
    REQUIRE(at != std::string::npos);
    return std::stod(text.substr(at + before.size()));
  };
  const test::Run sheets = test::phedra_cli({"outlines", tube, "--thickness-mm", "3", "--full-precision", "-o", (dir.path / "s.svg").string()});
  REQUIRE(sheets.code == 0);
  const double scale = number_after(sheets.out, "scale ");
  const test::Run mm = test::phedra_cli({"generate", tube, "--thickness-mm", "3", "--full-precision", "-o", (dir.path / "mm.stl").string()});
  REQUIRE(mm.code == 0);
  CHECK(number_after(mm.out, "in millimetres, ") == Approx(scale).epsilon(1e-12));
  // The same plates in model units, T = 3 mm / scale: every vertex scaled by it.
  const test::Run units = test::phedra_cli({"generate", tube, "--thickness", format_number(3.0 / scale), "-o", (dir.path / "mu.stl").string()});
  REQUIRE(units.code == 0);
  CHECK_THAT(units.out, Contains("in model units (a slicer reads them as millimetres"));
  const auto floats = [](const std::string& stl) {
    std::vector<float> out;
    std::uint32_t count = 0;
    std::memcpy(&count, stl.data() + 80, 4);
    for (std::size_t k = 0; k < count; ++k) {
      for (std::size_t c = 3; c < 12; ++c) {
        float x = 0.0f;
        std::memcpy(&x, stl.data() + 84 + 50 * k + 4 * c, 4);
        out.push_back(x);
      }
    }
    return out;
  };
  const std::vector<float> a = floats(read_file(dir.path / "mm.stl")), b = floats(read_file(dir.path / "mu.stl"));
  REQUIRE(a.size() == b.size());
  REQUIRE(a.size() > 1000);
  double worst = 0.0, low = 1e300, high = -1e300;
  for (std::size_t k = 0; k < a.size(); ++k) {
    worst = std::max(worst, std::abs(a[k] - scale * b[k]));
    if (k % 3 == 0) { low = std::min(low, double(a[k])); high = std::max(high, double(a[k])); }
  }
  CHECK(worst < 1e-4);  // mm: float rounding of coordinates of about 100 mm
  // The overall size said is the file's (x here), to 0.01 mm.
  CHECK(number_after(mm.out, "overall ") == Approx(high - low).margin(0.01));
  // A 3MF in millimetres says so; the volume is said in mm^3.
  REQUIRE(test::phedra_cli({"generate", tube, "--thickness-mm", "3", "-o", (dir.path / "mm.3mf").string()}).code == 0);
  CHECK_THAT(read_file(dir.path / "mm.3mf"), Contains("unit=\"millimeter\""));
  CHECK_THAT(mm.out, Contains(" mm^3"));
}

TEST_CASE("thick plates: sample --thickness adds the plates at every t, on the panels", "[thick][cli]") {
  const std::string tube = presets + "/parallelogram-tube.json";
  const test::Run run = test::phedra_cli({"sample", tube, "--count", "5", "--thickness", "0.08"});
  REQUIRE(run.code == 0);
  const nlohmann::json j = nlohmann::json::parse(run.out);
  const nlohmann::json& plates = j["plates"];
  CHECK(plates["thickness"] == 0.08);
  CHECK(plates["side"] == "front");
  REQUIRE(plates["panels"].size() == 40);
  REQUIRE(plates["samples"].size() == 5);
  for (std::size_t s = 0; s < 5; ++s) {
    CHECK(plates["samples"][s]["t"] == j["samples"][s]["t"]);
    const nlohmann::json& motion = j["samples"][s]["vertices"];
    for (std::size_t k = 0; k < 40; ++k) {
      const nlohmann::json& vertices = plates["samples"][s]["vertices"][k];
      const std::size_t corners = (plates["triangles"][k].size() + 4) / 4;  // 4n - 4 triangles
      REQUIRE(vertices.size() == 2 * corners);
      const nlohmann::json& face = j["faces"][plates["panels"][k].get<std::size_t>()];
      for (std::size_t c = 0; c < corners; ++c) {  // the bottom: corners of the panel at that t
        double nearest = 1e300;
        for (const auto& v : face) {
          const nlohmann::json& m = motion[v.get<std::size_t>()];
          nearest = std::min(nearest, std::hypot(vertices[c][0].get<double>() - m[0].get<double>(),
                                                 vertices[c][1].get<double>() - m[1].get<double>(),
                                                 vertices[c][2].get<double>() - m[2].get<double>()));
        }
        CHECK(nearest < 1e-9);
      }
    }
  }
  CHECK(test::phedra_cli({"sample", tube, "--count", "5", "--thickness", "0"}).code == 2);
}

TEST_CASE("thick plates: errors", "[thick][cli]") {
  test::TempDir dir("thick-errors");
  const std::string tube = presets + "/parallelogram-tube.json";
  auto fails = [&](std::vector<std::string> args, const std::string& says, int code = 2) {
    std::ostringstream out, err;
    INFO(args[0] << " " << says);
    CHECK(cli::run(args, out, err) == code);
    CHECK_THAT(err.str(), Contains(says));
  };
  fails({"generate", tube, "-o", (dir.path / "a.stl").string()}, "--thickness: an STL file holds solids");
  fails({"generate", tube, "-o", (dir.path / "a.3mf").string()}, "--thickness: an 3MF file holds solids");
  fails({"generate", tube, "--thickness", "0.1", "-o", (dir.path / "a.glb").string()},
        "--thickness: thick plates are written as solids");
  fails({"generate", tube, "--thickness", "-1", "-o", (dir.path / "a.stl").string()}, "--thickness");
  fails({"check", tube, "--thickness", "0.1", "--plate-side", "up"}, "--plate-side");
  fails({"check", tube, "--thickness", "3"}, "does not fit on panel");
  fails({"check", presets + "/anti-parallelogram-tube.json", "--thickness", "0.1"},
        "--thickness: the design is not buildable at t* without thickness");
  fails({"check", tube, "--thickness", "0.1", "--geometry-only"}, "drop --geometry-only");
  CHECK(fs::is_empty(dir.path));
  CHECK_THROWS_AS(plate_side_from_string("sideways"), InvalidInputError);
}

TEST_CASE("thick plates on cut sheets: numbered plates inside their panels, kerf, assembly pages, material", "[thick][sheets]") {
  // (under the sanitizers: the tube's 40 plates, not the grid's 216)
  const Design design = load_design(presets + (sanitized ? "/parallelogram-tube.json" : "/grid-3x3.json"));
  const std::size_t plates = sanitized ? 40 : 216;
  CutSheetOptions options;
  options.model_mm = 400.0;
  options.plates = PlateCut{3.0, 0.2, PlateSide::automatic};
  const CutSheets sheets = cut_sheets(design, options);
  REQUIRE(sheets.thick);
  CHECK(sheets.thick->thickness == Approx(3.0 / sheets.scale));
  CHECK(sheets.pieces.size() == plates);
  CHECK(sheets.piece_pages >= 1);
  CHECK(sheets.pages.size() > sheets.piece_pages);  // the assembly pages follow
  CHECK(sheets.material_used() > 0.1);
  CHECK(sheets.material_used() < 1.0);
  double area = 0.0;
  for (std::size_t k = 0; k < sheets.pieces.size(); ++k) {
    const Piece& piece = sheets.pieces[k];
    INFO("piece " << k);
    CHECK(piece.number == k + 1);
    REQUIRE(piece.cut);
    REQUIRE(piece.panels.size() == 1);
    area += 0.5 * std::abs(signed_area2(*piece.cut));
    // The cut runs half the kerf outside the plate's top face, which lies inside the panel:
    // every cut corner within the panel grown by half the kerf (and a rounding margin).
    Polygon2 panel = piece.panels[0].outline;
    if (signed_area2(panel) < 0.0) std::reverse(panel.begin(), panel.end());
    for (const Vec2& c : *piece.cut) {
      for (std::size_t e = 0; e < panel.size(); ++e) {
        const Vec2 a = panel[e], b = panel[(e + 1) % panel.size()];
        if ((b - a).norm() < 1e-9) continue;
        CHECK(cross((b - a).normalized(), c - a) >= -0.1 - 1e-6);  // at most half the kerf outside an edge
      }
    }
    // Its name: the number and the panel.
    const std::string name = std::to_string(piece.number) + " P" + std::to_string(piece.panels[0].panel);
    CHECK(std::any_of(piece.labels.begin(), piece.labels.end(), [&](const SheetText& t) { return t.text == name; }));
  }
  CHECK(area == Approx(sheets.cut_area_mm2));
  // The assembly pages name every piece, the first as the start.
  std::string assembly;
  for (std::size_t p = sheets.piece_pages; p < sheets.pages.size(); ++p) {
    for (const SheetText& t : sheets.pages[p].texts) assembly += t.text + "\n";
  }
  CHECK_THAT(assembly, Contains("\n1  P0, page "));
  CHECK_THAT(assembly, Contains(": start here"));
  CHECK_THAT(assembly, Contains("\n" + std::to_string(plates) + "  P"));
  CHECK_THAT(assembly, Contains("hinge to 1 (S"));
  // The last page: views of the assembly growing, up to 12, each group of pieces
  // once (orange), every panel in every view (a view draws each panel once),
  // joined panels grey in later views, inside the page; captions in order.
  {
    const SheetPage& views = sheets.pages.back();
    const std::size_t panels = sheets.thick->plates, count = std::min<std::size_t>(plates, 12);
    std::size_t view_fills = 0, added = 0, joined = 0;
    for (const SheetFill& f : views.fills) {
      const bool view = f.style == FillStyle::view_added || f.style == FillStyle::view_joined || f.style == FillStyle::view_later;
      view_fills += view ? 1 : 0;
      added += f.style == FillStyle::view_added ? 1 : 0;
      joined += f.style == FillStyle::view_joined ? 1 : 0;
      for (const Vec2& c : f.outline) {
        CHECK(c.allFinite());
        CHECK((c.array() >= 0.0).all());
        CHECK((c.array() <= sheets.page.array()).all());
      }
    }
    CHECK(view_fills == count * panels);
    CHECK(added == plates);  // each piece (one panel) orange in exactly one view
    CHECK(joined > 0);
    std::string captions;
    for (const SheetText& t : views.texts) captions += t.text + "\n";
    CHECK_THAT(captions, Contains("assembly in views"));
    CHECK_THAT(captions, Contains("pieces 1-"));
    CHECK_THAT(captions, Contains("-" + std::to_string(plates) + "\n"));
  }
  // Every hinge edge drawn as a hinge line; a kerf of 0 puts the cut on the top face.
  std::size_t hinge_lines = 0;
  for (std::size_t p = 0; p < sheets.piece_pages; ++p) {
    for (const SheetLine& l : sheets.pages[p].lines) hinge_lines += l.style == LineStyle::hinge ? 1 : 0;
  }
  std::size_t sides = 0;
  for (const Piece& piece : sheets.pieces) sides += piece.seams.size();
  CHECK(hinge_lines == sides + 1);  // and one in the key on the first page
  options.plates->kerf_mm = 0.0;
  const CutSheets exact = cut_sheets(design, options);
  CHECK(exact.cut_area_mm2 < sheets.cut_area_mm2);
}

TEST_CASE("thick plates on cut sheets: the command, its files and its errors", "[thick][sheets][cli]") {
  test::TempDir dir("thick-sheets");
  const std::string tube = presets + "/parallelogram-tube.json";
  const test::Run run = test::phedra_cli({"outlines", tube, "--thickness-mm", "2", "--kerf", "0.15", "-o", (dir.path / "t.pdf").string()});
  REQUIRE(run.code == 0);
  CHECK_THAT(run.out, Contains("40 pieces (plates) of 40 panels, 76 hinges"));
  CHECK_THAT(run.out, Contains("material: 1 sheet of 210 x 297 mm"));
  CHECK_THAT(run.out, Contains("assembly on pages 2-3 (the order, then views of it)"));
  CHECK(read_file(dir.path / "t.pdf").rfind("%PDF", 0) == 0);
  REQUIRE(test::phedra_cli({"outlines", tube, "--thickness-mm", "2", "-o", (dir.path / "t.dxf").string()}).code == 0);
  CHECK_THAT(read_file(dir.path / "t.dxf"), Contains("\nHINGE\n"));
  const test::Run kerf = test::phedra_cli({"outlines", tube, "--kerf", "0.2", "-o", (dir.path / "k.pdf").string()});
  CHECK(kerf.code == 2);
  CHECK_THAT(kerf.err, Contains("--kerf: a kerf is for plates cut from sheet material"));
  CHECK(test::phedra_cli({"outlines", tube, "--thickness-mm", "2", "--kerf", "-1", "-o", (dir.path / "k.pdf").string()}).code == 2);
  const test::Run strips = test::phedra_cli({"outlines", tube, "--thickness-mm", "2", "--pieces", "strips", "-o", (dir.path / "k.pdf").string()});
  CHECK(strips.code == 2);
  CHECK_THAT(strips.err, Contains("--pieces: plates cut from sheet material are one piece each"));
  const test::Run thick = test::phedra_cli({"outlines", tube, "--thickness-mm", "80", "-o", (dir.path / "k.pdf").string()});
  CHECK(thick.code == 2);
  // In the unit it was given in (issue 38): millimetres, as --thickness-mm.
  CHECK_THAT(thick.err, Contains("--thickness-mm: plates 80 mm thick do not fit on panel"));
  CHECK_FALSE(fs::exists(dir.path / "k.pdf"));
  const test::Run checked = test::phedra_cli({"check", tube, "--thickness-mm", "80"});
  CHECK(checked.code == 2);
  CHECK_THAT(checked.err, Contains("--thickness-mm: plates 80 mm thick do not fit on panel"));
  // --thickness-mm on check means what it means on the sheets: millimetres at their scale.
  const Design design = load_design(tube);
  CutSheetOptions options;
  options.model_mm = 400.0;
  options.plates = PlateCut{3.0, 0.0, PlateSide::automatic};
  const CutSheets sheets = cut_sheets(design, options);
  const test::Run check = test::phedra_cli({"check", tube, "--thickness-mm", "3", "--model-size", "400", "--json"});
  REQUIRE(check.code == 0);
  CHECK(nlohmann::json::parse(check.out)["thick"]["thickness"].get<double>() == Approx(sheets.thick->thickness));
  const test::Run scaled = test::phedra_cli({"check", tube, "--thickness-mm", "3", "--scale", "30", "--json"});
  CHECK(nlohmann::json::parse(scaled.out)["thick"]["thickness"].get<double>() == Approx(0.1));
  CHECK(test::phedra_cli({"check", tube, "--thickness", "0.1", "--thickness-mm", "3"}).code == 2);
  CHECK(test::phedra_cli({"check", tube, "--scale", "30"}).code == 2);
}
