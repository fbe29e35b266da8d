// Fabrication outlines (issue 7, item 6): flat panels true to size, hinge labels
// that pair up, tabs, a sheet without overlaps, SVG and DXF, phedra outlines.

#include "cli.h"
#include "phedra/assembly_mesh.h"
#include "phedra/flat_outlines.h"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

using namespace phedra;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

const std::string presets = PHEDRA_PRESETS_DIR;

int phedra_cli(const std::vector<std::string>& args, std::string* err = nullptr) {
  std::ostringstream out, e;
  const int code = cli::run(args, out, e);
  if (err) *err = e.str();
  return code;
}

}  // namespace

TEST_CASE("flat outlines are the panels true to size, hinges pair up, nothing overlaps", "[outlines]") {
  for (const char* name : {"default", "parallelogram-tube", "grid-3x3", "merged-tube", "edge-sharing-pair"}) {
    CAPTURE(name);
    const Design design = load_design(presets + "/" + name + ".json");
    OutlineOptions options;
    options.tabs = true;
    options.scale = 7.0;
    const OutlineSheet sheet = flat_outlines(design, options);
    const AssemblyMesh mesh = panel_mesh(design);
    const Points x = mesh.positions(design.assembly.evaluate(design.assembly.t_star()));
    REQUIRE(sheet.panels.size() == mesh.faces.size());
    const double size = design.assembly.model_size();
    std::map<std::size_t, std::vector<double>> hinge_lengths;
    std::size_t tabs = 0;
    for (const FlatPanel& p : sheet.panels) {
      const Quad& q = mesh.faces[p.face];
      // Edges and both diagonals keep their lengths (times the scale): the panel's true shape.
      for (int k = 0; k < 4; ++k) {
        const double flat = (p.corners[(k + 1) % 4] - p.corners[k]).norm();
        CHECK(flat == Approx(7.0 * (x[q[(k + 1) % 4]] - x[q[k]]).norm()).margin(1e-9 * size));
        if (p.hinge[k]) hinge_lengths[*p.hinge[k]].push_back(flat);
        tabs += p.tab[k] ? 1 : 0;
      }
      for (int k = 0; k < 2; ++k) {
        CHECK((p.corners[k + 2] - p.corners[k]).norm() ==
              Approx(7.0 * (x[q[k + 2]] - x[q[k]]).norm()).margin(1e-9 * size));
      }
      for (const Vec2& c : p.corners) {
        CHECK(c.x() >= 0.0);
        CHECK(c.y() >= 0.0);
        CHECK(c.x() <= sheet.width);
        CHECK(c.y() <= sheet.height);
      }
    }
    // Every hinge labels two or more edges of equal length, and has one tab.
    CHECK(hinge_lengths.size() == sheet.hinges);
    for (const auto& [id, lengths] : hinge_lengths) {
      CHECK(lengths.size() >= 2);
      for (double l : lengths) CHECK(l == Approx(lengths.front()).margin(1e-9 * size));
    }
    CHECK(tabs == sheet.hinges);
    // Panel bounding boxes (with their tabs) do not overlap.
    std::vector<std::pair<Vec2, Vec2>> boxes;
    for (const FlatPanel& p : sheet.panels) {
      Vec2 lo = p.corners[0], hi = p.corners[0];
      for (const Vec2& c : p.corners) lo = lo.cwiseMin(c), hi = hi.cwiseMax(c);
      for (int k = 0; k < 4; ++k) {
        if (p.tab[k]) {
          for (const Vec2& c : sheet.tab_polygon(p, k)) lo = lo.cwiseMin(c), hi = hi.cwiseMax(c);
        }
      }
      boxes.push_back({lo, hi});
    }
    std::size_t overlaps = 0;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      for (std::size_t j = i + 1; j < boxes.size(); ++j) {
        const bool apart = (boxes[i].second.array() < boxes[j].first.array() + 1e-9).any() ||
                           (boxes[j].second.array() < boxes[i].first.array() + 1e-9).any();
        overlaps += apart ? 0 : 1;
      }
    }
    CHECK(overlaps == 0);
    // DXF: code/value pairs; 4 lines a panel and 3 more a tab; SVG: one group a panel.
    const std::string dxf = outlines_dxf(sheet);
    CHECK(std::count(dxf.begin(), dxf.end(), '\n') % 2 == 0);
    std::size_t lines = 0;
    for (std::size_t at = dxf.find("\nLINE\n"); at != std::string::npos; at = dxf.find("\nLINE\n", at + 1)) ++lines;
    CHECK(lines == 4 * sheet.panels.size() + 3 * tabs);
    CHECK(dxf.find("nan") == std::string::npos);
    CHECK_THAT(dxf, Contains("0\nEOF\n"));
    const std::string svg = outlines_svg(sheet);
    std::size_t groups = 0;
    for (std::size_t at = svg.find("id=\"panel-"); at != std::string::npos; at = svg.find("id=\"panel-", at + 1)) ++groups;
    CHECK(groups == sheet.panels.size());
  }
}

TEST_CASE("phedra outlines writes SVG and DXF and refuses bad options", "[outlines][cli]") {
  const fs::path dir = fs::temp_directory_path() / ("phedra-outlines-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string tube = presets + "/parallelogram-tube.json";
  CHECK(phedra_cli({"outlines", tube, "-o", (dir / "t.svg").string(), "--tabs"}) == 0);
  CHECK(fs::file_size(dir / "t.svg") > 1000);
  CHECK(phedra_cli({"outlines", tube, "-o", (dir / "t.dxf").string(), "--scale", "25"}) == 0);
  std::string err;
  CHECK(phedra_cli({"outlines", tube, "-o", (dir / "t.pdf").string()}, &err) == 2);
  CHECK_THAT(err, Contains("unknown format \".pdf\""));
  CHECK(phedra_cli({"outlines", tube, "-o", (dir / "u.svg").string(), "--tabs", "--tab-depth", "0.7"}, &err) == 2);
  CHECK_THAT(err, Contains("--tab-depth"));
  CHECK(phedra_cli({"outlines", tube, "-o", (dir / "u.svg").string(), "--scale", "0"}, &err) == 2);
  CHECK_THAT(err, Contains("--scale"));
  CHECK(!fs::exists(dir / "u.svg"));
  fs::remove_all(dir);
}
