// Parts laid flat for printing (issue 38, item 3): every part rigidly moved
// onto its largest face (the plates' largest face measured here from the
// plates' own corners), on its bed with the gap kept from the edges and from
// every other part, numbered as on the cut sheets; the command's files and
// errors. PrusaSlicer slices the files in tests/prusa/check_print_beds.sh.

#include "phedra/buildability.h"
#include "phedra/cut_sheets.h"
#include "phedra/design_preset.h"
#include "phedra/errors.h"
#include "phedra/hinge_pins.h"
#include "phedra/print_beds.h"
#include "phedra/sheet_geometry.h"
#include "phedra/thick_plates.h"
#include "support/cli_run.h"
#include "support/polygon_distance.h"
#include "support/test_files.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <map>

using namespace phedra;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

using test::presets;

/// The area of a planar polygon in 3D.
double area3(const std::vector<Vec3>& p) {
  Vec3 twice = Vec3::Zero();
  for (std::size_t k = 0; k < p.size(); ++k) twice += p[k].cross(p[(k + 1) % p.size()]);
  return 0.5 * twice.norm();
}

/// The distance between two convex polygons (0 when they overlap).
double distance(const Polygon2& a, const Polygon2& b) { return polygon_overlap(a, b) > 0.0 ? 0.0 : test::polygon_distance(a, b); }

/// Checks the layout of `solids` (mm): each part a proper rigid copy of its
/// solid, resting on z = 0 with that face's area, inside its bed by the gap,
/// the gap from every part on its bed.
void check_layout(const PrintLayout& layout, const std::vector<Solid>& solids) {
  REQUIRE(layout.parts.size() == solids.size());
  REQUIRE(layout.beds >= 1);
  std::vector<std::vector<std::size_t>> on_bed(layout.beds);
  std::vector<Polygon2> prints;
  for (std::size_t k = 0; k < solids.size(); ++k) {
    const PrintPart& part = layout.parts[k];
    const Solid& before = solids[k];
    CAPTURE(part.name);
    REQUIRE(part.bed < layout.beds);
    on_bed[part.bed].push_back(k);
    REQUIRE(part.solid.vertices.size() == before.vertices.size());
    REQUIRE(part.solid.triangles == before.triangles);
    // Rigid and proper: distances from two vertices kept, the volume kept (a mirror would negate it).
    double size = 0.0;
    for (std::size_t v = 0; v < before.vertices.size(); ++v) size = std::max(size, (before.vertices[v] - before.vertices[0]).norm());
    for (std::size_t v = 0; v < before.vertices.size(); ++v) {
      for (const std::size_t o : {std::size_t{0}, before.vertices.size() / 2}) {
        CHECK(std::abs((part.solid.vertices[v] - part.solid.vertices[o]).norm() - (before.vertices[v] - before.vertices[o]).norm()) <=
              1e-9 * size);
      }
    }
    CHECK(part.solid.volume() == Approx(before.volume()).epsilon(1e-9));
    // On the bed: nothing below z = 0, the base exactly there, its area the part's base area.
    double low = std::numeric_limits<double>::infinity(), base = 0.0;
    std::vector<Vec2> footprint;
    for (const Vec3& v : part.solid.vertices) {
      low = std::min(low, v.z());
      footprint.push_back(v.head<2>());
      CHECK(v.x() >= layout.gap - 1e-9);
      CHECK(v.y() >= layout.gap - 1e-9);
      CHECK(v.x() <= layout.bed.x() - layout.gap + 1e-9);
      CHECK(v.y() <= layout.bed.y() - layout.gap + 1e-9);
    }
    CHECK(low == 0.0);
    for (const auto& t : part.solid.triangles) {
      const Vec3 &a = part.solid.vertices[t[0]], &b = part.solid.vertices[t[1]], &c = part.solid.vertices[t[2]];
      if (a.z() == 0.0 && b.z() == 0.0 && c.z() == 0.0) {
        const Vec3 n = (b - a).cross(c - a);
        CHECK(n.z() < 0.0);  // outward: facing the bed
        base += 0.5 * n.norm();
      }
    }
    CHECK(base == Approx(part.base_area).epsilon(1e-9));
    prints.push_back(convex_hull(footprint));
  }
  std::size_t pairs = 0;
  for (const std::vector<std::size_t>& parts : on_bed) {
    CHECK_FALSE(parts.empty());
    for (std::size_t i = 0; i < parts.size(); ++i) {
      for (std::size_t j = i + 1; j < parts.size(); ++j) {
        CAPTURE(layout.parts[parts[i]].name, layout.parts[parts[j]].name);
        CHECK(distance(prints[parts[i]], prints[parts[j]]) >= layout.gap - 1e-6);
        ++pairs;
      }
    }
  }
  CHECK((solids.size() < 2 || pairs > 0));
}

struct Plates {
  Design design;
  ThickReport report;
  std::vector<Solid> solids;  // mm
  std::vector<std::string> names;
  std::size_t count = 0;
};

Plates plates_of(const std::string& preset, double thickness_mm, double mm_per_unit, bool pins) {
  Plates p{load_design(presets + "/" + preset), {}, {}, {}, 0};
  ThickOptions options;
  options.thickness = thickness_mm / mm_per_unit;
  options.hinge_gap = pins ? pin_hinge_gap(options.thickness) : 0.0;
  p.report = check_thickness(p.design, assess_buildability(p.design), options);
  const ThickPlates plates = thick_plates(p.design, p.report);
  const Points x = plates.positions(p.design.assembly.t_star());
  p.solids = plates.solids(x);
  p.count = p.solids.size();
  for (std::size_t k = 0; k < p.count; ++k) p.names.push_back("plate_P" + std::to_string(plates.panel(k)));
  if (pins) {
    HingeParts parts = pin_hinge_parts(plates, x, pin_layout(plates, {plates.design().assembly.t_star()}));
    for (std::size_t k = 0; k < parts.solids.size(); ++k) {
      p.solids.push_back(parts.solids[k]);
      p.names.push_back(parts.names[k]);
    }
  }
  for (Solid& s : p.solids) {
    for (Vec3& v : s.vertices) v *= mm_per_unit;
  }
  // The plates' largest faces, from their own corners (bottom: the panel less the gap; top: the bevels' inset).
  return p;
}

}  // namespace

TEST_CASE("parts laid flat: on their largest face, on the bed, the gap kept, rigid copies", "[print]") {
  struct Case {
    std::string preset;
    double thickness_mm, scale;
    bool pins;
    Vec2 bed;
  };
  std::vector<Case> cases{{"parallelogram-tube.json", 2.0, 23.4, true, Vec2(200.0, 200.0)}};
#ifndef PHEDRA_SANITIZE_BUILD  // the code paths above (10x slower there); the other presets in the Release run
  cases.push_back({"parallelogram-tube.json", 3.0, 23.4, false, Vec2(200.0, 200.0)});
  cases.push_back({"grid-3x3.json", 1.0, 28.3, false, Vec2(250.0, 210.0)});
  cases.push_back({"default.json", 1.0, 10.0, false, Vec2(120.0, 120.0)});
#endif
  for (const Case& c : cases) {
    CAPTURE(c.preset, c.pins);
    const Plates p = plates_of(c.preset, c.thickness_mm, c.scale, c.pins);
    const PrintLayout layout = lay_flat(p.solids, p.names, c.bed);
    check_layout(layout, p.solids);
    // A plate lies on its larger face (the bottom, the panel's, or the top), measured from its corners.
    const ThickPlates plates = thick_plates(p.design, p.report);
    for (std::size_t k = 0; k < p.count; ++k) {
      const double largest = c.scale * c.scale * std::max(area3(plates.bottom(k)), area3(plates.top(k)));
      CAPTURE(k);
      CHECK(layout.parts[k].base_area == Approx(largest).epsilon(1e-9));
    }
    // Nothing to support: no face above the bed looks down more steeply than 45
    // degrees (knuckles and pins then stand on an end, their round profile
    // printed layer by layer).
    for (const PrintPart& part : layout.parts) {
      double down = 0.0;
      for (const auto& t : part.solid.triangles) {
        const Vec3 &a = part.solid.vertices[t[0]], &b = part.solid.vertices[t[1]], &cc = part.solid.vertices[t[2]];
        const Vec3 n = (b - a).cross(cc - a);
        if (std::max({a.z(), b.z(), cc.z()}) > 0.0 && n.z() < -std::sqrt(0.5) * n.norm()) down += 0.5 * n.norm();
      }
      CAPTURE(part.name);
      CHECK(down == 0.0);
    }
  }
}

TEST_CASE("parts laid flat: plates numbered as on the plate cut sheets", "[print]") {
#ifdef PHEDRA_SANITIZE_BUILD
  const std::vector<std::string> shipped{"parallelogram-tube.json"};
#else
  const std::vector<std::string> shipped{"parallelogram-tube.json", "grid-3x3.json", "default.json"};
#endif
  for (const std::string& preset : shipped) {
    CAPTURE(preset);
    const Design design = load_design(presets + "/" + preset);
    const std::vector<std::size_t> numbers = plate_sheet_numbers(design);
    CutSheetOptions options;
    options.plates = PlateCut{1.0, 0.0, PlateSide::automatic};
    const CutSheets sheets = cut_sheets(design, options);
    std::size_t checked = 0;
    for (const Piece& piece : sheets.pieces) {
      REQUIRE(piece.panels.size() == 1);
      CHECK(numbers.at(piece.panels[0].panel) == piece.number);
      ++checked;
    }
    CHECK(checked == static_cast<std::size_t>(std::count_if(numbers.begin(), numbers.end(), [](std::size_t n) { return n > 0; })));
  }
}

TEST_CASE("parts laid flat: bed sizes, and a part that fits no bed, refused", "[print][errors]") {
  CHECK(bed_size_from_string("250x210") == Vec2(250.0, 210.0));
  for (const std::string bad : {"200", "200x", "x200", "200x200x200", "abcxdef", "5x200", "200x1e9", "nanxnan", "200 x 200"}) {
    CAPTURE(bad);
    CHECK_THROWS_AS(bed_size_from_string(bad), InvalidInputError);
  }
  const Plates p = plates_of("parallelogram-tube.json", 3.0, 23.4, false);
  try {
    lay_flat(p.solids, p.names, Vec2(20.0, 20.0));
    FAIL("a 20 mm bed holds the tube's plates");
  } catch (const InvalidInputError& e) {
    CHECK(e.field() == "--bed");
    CHECK_THAT(e.reason(), Contains("laid flat: it fits no 20 x 20 mm bed with 5 mm around it (a bed of"));
  }
}

TEST_CASE("generate --layout print: one file a bed, the plates' numbers, and its errors", "[print][cli]") {
  const fs::path dir = fs::temp_directory_path() / "phedra-print-beds";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string tube = presets + "/parallelogram-tube.json";
  {  // One bed: the file named as asked.
    const test::Run r = test::phedra_cli({"generate", tube, "--thickness-mm", "3", "--layout", "print", "-o", (dir / "tube.3mf").string()});
    CAPTURE(r.out, r.err);
    REQUIRE(r.code == 0);
    CHECK(fs::exists(dir / "tube.3mf"));
    CHECK_THAT(r.out, Contains("40 plates of \"parallelogram-tube\" laid flat on 1 bed of 200 x 200 mm (each on its largest face, nothing to support; 5 mm apart), in millimetres"));
  }
  {  // Several beds: parts-1.stl, parts-2.stl, ...; a line a bed.
    const test::Run r = test::phedra_cli({"generate", tube, "--thickness-mm", "3", "--layout", "print", "--bed", "80x80", "-o",
                                          (dir / "parts.stl").string()});
    CAPTURE(r.out, r.err);
    REQUIRE(r.code == 0);
    std::size_t beds = 0;
    while (fs::exists(dir / ("parts-" + std::to_string(beds + 1) + ".stl"))) ++beds;
    CHECK(beds >= 2);
    CHECK_FALSE(fs::exists(dir / "parts.stl"));
    CHECK_THAT(r.out, Contains("on " + std::to_string(beds) + " beds of 80 x 80 mm"));
    CHECK_THAT(r.out, Contains("  bed " + std::to_string(beds) + " (" + (dir / ("parts-" + std::to_string(beds) + ".stl")).string() + "): "));
  }
  struct Refusal {
    std::vector<std::string> args;
    std::string says;
  };
  const std::string out = (dir / "bad.3mf").string();
  for (const Refusal& r : std::vector<Refusal>{
           {{"--thickness", "0.1", "--layout", "print"}, "--layout: parts laid flat on a printer's bed are in millimetres: give --thickness-mm"},
           {{"--thickness-mm", "3", "--bed", "200x200"}, "--bed: the bed is for parts laid flat: add --layout print"},
           {{"--thickness-mm", "3", "--layout", "print", "--at", "0"}, "--at: parts laid flat for printing have no pose"},
           {{"--thickness-mm", "3", "--layout", "print", "--bed", "200"}, "--bed: expected WxH in millimetres"},
           {{"--thickness-mm", "3", "--layout", "print", "--bed", "20x20"}, "--bed: part plate_"},
           {{"--thickness-mm", "3", "--layout", "flat"}, "--layout"}}) {
    std::vector<std::string> args{"generate", tube, "-o", out};
    args.insert(args.end(), r.args.begin(), r.args.end());
    const test::Run run = test::phedra_cli(args);
    CAPTURE(args, run.err);
    CHECK(run.code == 2);
    CHECK_THAT(run.err, Contains(r.says));
    CHECK_FALSE(fs::exists(out));
  }
  fs::remove_all(dir);
}
