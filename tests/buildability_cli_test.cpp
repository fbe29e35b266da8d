// Buildability as the commands say it (issue 13): one test per message, the
// same panels named by every command and stored in every export, and the
// shipped presets' buildability pinned.

#include "support/test_files.h"
#include "phedra/buildability.h"
#include "support/cli_run.h"
#include "phedra/design_preset.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
#include <unistd.h>

using phedra::test::data;
using phedra::test::presets;
using phedra::test::read_json;

using namespace phedra;
using phedra::test::phedra_cli;
using phedra::test::Run;
using Catch::Matchers::Contains;
using json = nlohmann::json;
namespace fs = std::filesystem;

namespace {

/// A random design (a reference case) with every kind of invalid panel.
const std::string bow_ties = data + "/cases/open-mixed-tilted-axis.json";
/// Simple panels; a hinge folds through below t = 0.2702.
const std::string partly = data + "/partly-buildable.json";

/// The numbers of the invalid panels as `check --json` lists them.
std::vector<std::size_t> invalid_of(const std::string& preset) {
  const Run r = phedra_cli({"check", preset, "--json", "--samples", "3"});
  const json report = json::parse(r.out);
  std::vector<std::size_t> out;
  for (const json& p : report["buildability"]["invalid_panels"]) out.push_back(p["panel"]);
  return out;
}

struct ScratchDir {
  fs::path path = fs::temp_directory_path() / ("phedra-buildable-test-" + std::to_string(::getpid()));
  ScratchDir() { fs::create_directories(path); }
  ~ScratchDir() { fs::remove_all(path); }
  std::string operator/(const std::string& name) const { return (path / name).string(); }
};

}  // namespace

TEST_CASE("check: FAIL for a design with bow-ties, with each panel's cause and the field to change", "[buildability][cli]") {
  const Run r = phedra_cli({"check", bow_ties});
  CHECK(r.code == 1);
  CHECK_THAT(r.out, Contains("FAIL: open-mixed-tilted-axis: the geometry holds, but the design is not buildable"));
  CHECK_THAT(r.out, Contains("geometry PASS"));
  CHECK_THAT(r.out, Contains("buildability: not buildable: 17 of 42 panels cannot be cut as one plate (17 bow-ties: panels 4, 5,"));
  CHECK_THAT(r.out, Contains(") is a bow-tie: "));
  CHECK_THAT(r.out, Contains("    change: ") && Contains(" by more than about "));
  CHECK_THAT(r.out, Contains("... and 9 more (--json lists every panel with its cause)"));
  // The JSON lists every one, with its cause and hints.
  const json j = json::parse(phedra_cli({"check", bow_ties, "--json"}).out);
  CHECK(j["passed"] == false);
  CHECK(j["geometry_passed"] == true);
  CHECK(j["buildability"]["invalid_panels"].size() == 17);
  for (const json& p : j["buildability"]["invalid_panels"]) {
    CHECK(p["cause"] != "none");
    CHECK(!p["why"].get<std::string>().empty());
  }
}

TEST_CASE("check --geometry-only: the geometry alone, the exit code ignores buildability", "[buildability][cli]") {
  const Run r = phedra_cli({"check", bow_ties, "--geometry-only"});
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Contains("PASS: open-mixed-tilted-axis: the geometry holds (buildability not checked: --geometry-only)"));
  CHECK(r.out.find("buildability:") == std::string::npos);
}

TEST_CASE("the causes in the input's terms: every kind of message", "[buildability][cli]") {
  const std::string text = phedra_cli({"check", bow_ties, "--json"}).out;
  // '+' apex between its neighbours; '-' hourglass (vanishing height); '-' transversal
  // edges crossing (the collineation's fixed height); boundary faces; reversed edges.
  CHECK_THAT(text, Contains("with sign '+' at S_") && Contains(") lies between those of S_") &&
                       Contains("make it the highest or the lowest of the three"));
  CHECK_THAT(text, Contains("so the face is an hourglass about it; with sign '-' at S_") &&
                       Contains("lies on the far side of the vanishing height"));
  CHECK_THAT(text, Contains("so the face's transversal edges cross; with sign '-' at S_") &&
                       Contains("which the collineation keeps fixed"));
  CHECK_THAT(text, Contains("a boundary-column face: its transversal edge V_") &&
                       Contains("is shorter than in the axial net (") && Contains("longer than that, the face is convex"));
  CHECK_THAT(text, Contains("in the parallel net (its length over the axial net's, signed) while the panel's other edges "
                            "have the other sign") &&
                       Contains("point opposite ways"));
  // A reversed trajectory segment (column 0 of the general net).
  CHECK_THAT(phedra_cli({"check", data + "/cases/open-all-plus.json"}).out,
             Contains("points against the axial trajectory)"));
}

TEST_CASE("check and info on an anti-parallelogram tube: not buildable by its kind", "[buildability][cli]") {
  const Run r = phedra_cli({"check", presets + "/anti-parallelogram-tube.json"});
  CHECK(r.code == 1);
  CHECK_THAT(r.out, Contains("buildability: not buildable, by its kind: an anti-parallelogram tube's walls cross each "
                             "other along a line at every t"));
  CHECK_THAT(r.out, Contains("panels: 32 distinct, 0 bow-tie"));
  // Its own generate warning says no more than that (no field can fix it).
  ScratchDir dir;
  const Run g = phedra_cli({"generate", presets + "/anti-parallelogram-tube.json", "-o", dir / "a.json", "--count", "3"});
  CHECK(g.code == 0);
  CHECK_THAT(g.err, Contains("by its kind"));
  CHECK(g.err.find("phedra check") == std::string::npos);
}

TEST_CASE("a collision at t*, and a design buildable over part of its interval", "[buildability][cli]") {
  const Run crossing = phedra_cli({"check", data + "/self-intersecting.json"});
  CHECK(crossing.code == 1);
  CHECK_THAT(crossing.out, Contains("buildability: not buildable: the configuration at t* intersects itself: panel "));
  const Run part = phedra_cli({"check", partly});
  CHECK(part.code == 1);
  CHECK_THAT(part.out, Contains("buildability: buildable over [0.3067, 0.313276] only (57.25 % of the flexion interval"));
  CHECK_THAT(part.out, Contains("  above t = 0.313276") && Contains("folds shut and through"));
  const Run info = phedra_cli({"info", partly});
  CHECK_THAT(info.out, Contains("buildability:      buildable over [") && Contains("(phedra check names the cause"));
}

TEST_CASE("generate and sample warn when what they write is not buildable, and say how to get the buildable part",
          "[buildability][cli]") {
  ScratchDir dir;
  // Bow-ties: no buildable part; the file is still written.
  const Run g = phedra_cli({"generate", bow_ties, "-o", dir / "b.glb", "-q"});
  CHECK(g.code == 0);
  CHECK(fs::exists(dir / "b.glb"));
  CHECK_THAT(g.err, Contains("phedra: warning: what is written ([") && Contains("]) is not buildable: not buildable: 17 of 42"));
  CHECK_THAT(g.err, Contains("names the cause of each invalid panel and the field to change"));
  // Partly buildable: --no-self-intersection writes the buildable part.
  const Run p = phedra_cli({"generate", partly, "-o", dir / "p.fold", "--count", "3"});
  CHECK_THAT(p.err, Contains("; --no-self-intersection writes the buildable part [0.3067, 0.313276]"));
  CHECK_THAT(p.err, Contains("`phedra intersections ") && Contains("` shows where the motion collides"));
  const Run restricted = phedra_cli({"generate", partly, "-o", dir / "r.fold", "--count", "3", "--no-self-intersection"});
  CHECK(restricted.code == 0);
  CHECK(restricted.err.find("warning") == std::string::npos);
  // A static export inside the buildable part: no warning; outside: one.
  const Run inside = phedra_cli({"generate", partly, "-o", dir / "i.obj", "--at", "0.31"});
  CHECK(inside.err.find("warning") == std::string::npos);
  const Run outside = phedra_cli({"generate", partly, "-o", dir / "o.obj", "--at", "0.316"});
  CHECK_THAT(outside.err, Contains("what is written (t = 0.316) is not buildable"));
  // sample names the buildable part.
  const Run s = phedra_cli({"sample", partly, "--count", "3", "-o", dir / "s.json"});
  CHECK(s.code == 0);
  CHECK_THAT(s.err, Contains("; the buildable part is [0.3067, 0.313276]"));
  const Run fine = phedra_cli({"sample", presets + "/default.json", "--count", "3"});
  CHECK(fine.err.empty());
}

TEST_CASE("every command and every export names the same invalid panels", "[buildability][cli]") {
  ScratchDir dir;
  const std::vector<std::size_t> invalid = invalid_of(bow_ties);
  REQUIRE(invalid.size() == 17);
  // info
  const json info = json::parse(phedra_cli({"info", bow_ties, "--json"}).out);
  CHECK(info["panels"]["bow_tie"] == 17);
  CHECK(info["panels"]["distinct"] == 42);
  CHECK(info["buildability"]["invalid_panels"].get<std::vector<std::size_t>>() == invalid);
  // intersections
  const json inter = json::parse(phedra_cli({"intersections", bow_ties, "--json"}).out);
  CHECK(inter["invalid_panels"].size() == 17);
  for (std::size_t k = 0; k < invalid.size(); ++k) CHECK(inter["invalid_panels"][k]["face"] == invalid[k]);
  // glTF, FOLD, motion JSON
  REQUIRE(phedra_cli({"generate", bow_ties, "-o", dir / "b.gltf", "-q"}).code == 0);
  CHECK(read_json(dir / "b.gltf")["asset"]["extras"]["phedra"]["buildability"]["invalid_panels"].get<std::vector<std::size_t>>() ==
        invalid);
  REQUIRE(phedra_cli({"generate", bow_ties, "-o", dir / "b.fold", "--count", "2"}).code == 0);
  CHECK(read_json(dir / "b.fold")["phedra:buildability"]["invalid_panels"].get<std::vector<std::size_t>>() == invalid);
  REQUIRE(phedra_cli({"sample", bow_ties, "--count", "2", "-o", dir / "b.json"}).code == 0);
  const json motion = read_json(dir / "b.json");
  CHECK(motion["buildability"]["invalid_panels"].get<std::vector<std::size_t>>() == invalid);
  CHECK(motion["buildability"]["buildable"] == false);
  // OBJ and PLY say it in a comment.
  REQUIRE(phedra_cli({"generate", bow_ties, "-o", dir / "b.obj"}).code == 0);
  std::ifstream obj(dir / "b.obj");
  std::string first;
  std::getline(obj, first);
  CHECK_THAT(first, Contains("# phedra buildability: not buildable: 17 of 42 panels"));
  // outlines: the same panels filled red on the cut sheets; a warning names them.
  const Run o = phedra_cli({"outlines", bow_ties, "-o", dir / "b.svg", "--pieces", "panels"});
  CHECK(o.code == 0);
  CHECK_THAT(o.err, Contains("phedra: warning: 17 of 42 panels cannot be cut as one plate (filled red on the sheets): panels 4, 5,"));
  CHECK_THAT(o.out, Contains("buildability: not buildable: 17 of 42"));
  std::vector<std::size_t> red;
  for (std::size_t page = 1; fs::exists(dir / ("b-" + std::to_string(page) + ".svg")); ++page) {
    std::ifstream svg_in(dir / ("b-" + std::to_string(page) + ".svg"));
    const std::string svg((std::istreambuf_iterator<char>(svg_in)), std::istreambuf_iterator<char>());
    const std::regex red_fill("class=\"not-cuttable\" data-panel=\"([0-9]+)\"");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), red_fill); it != std::sregex_iterator(); ++it) {
      red.push_back(std::stoul((*it)[1]));
    }
    if (page == 1) CHECK_THAT(svg, Contains("not one plate"));  // (the key is on the first sheet)
  }
  std::sort(red.begin(), red.end());
  CHECK(red == invalid);
  // metrics
  const Run m = phedra_cli({"metrics", bow_ties, "--samples", "3", "-o", dir / "m.json"});
  CHECK_THAT(m.out, Contains("buildability: not buildable: 17 of 42"));
  CHECK(read_json(dir / "m.json")["buildability"]["invalid_panels"].get<std::vector<std::size_t>>() == invalid);
}

TEST_CASE("arrays: a wall two cells share is one panel, numbered as in the export", "[buildability][cli]") {
  ScratchDir dir;
  const std::string grid = presets + "/grid-3x3.json";
  const json info = json::parse(phedra_cli({"info", grid, "--json"}).out);
  CHECK(info["panels"]["distinct"] == 216);       // 9 cells x 4 sides x 9 strips - 108 shared walls
  CHECK(info["panels"]["shared_walls"] == 108);
  CHECK(info["faces"] == 216);
  REQUIRE(phedra_cli({"generate", grid, "-o", dir / "g.gltf", "-q", "--nodes"}).code == 0);
  const json gltf = read_json(dir / "g.gltf");
  std::size_t panel_nodes = 0;
  for (const json& node : gltf["nodes"]) panel_nodes += node.contains("mesh") ? 1 : 0;
  CHECK(panel_nodes == 216);
  REQUIRE(phedra_cli({"generate", grid, "-o", dir / "g.fold", "--count", "2"}).code == 0);
  const json fold = read_json(dir / "g.fold");
  CHECK(fold["faces_vertices"].size() == 216);
  CHECK(fold["frame_attributes"][1] == "nonManifold");
  // Every vertex the cells share is one vertex: 10 profiles x 16 grid lines' points.
  CHECK(fold["vertices_coords"].size() == 160);
  const Run text = phedra_cli({"check", grid});
  CHECK_THAT(text.out, Contains("panels: 216 distinct (108 walls shared by two cells, counted once), 0 bow-tie, 0 degenerate"));
}

TEST_CASE("generate warns when the morph targets cannot keep the tolerance", "[buildability][cli]") {
  ScratchDir dir;
  const Run r = phedra_cli({"generate", presets + "/default.json", "-o", dir / "c.glb", "--cycle", "--morph", "--tolerance", "2e-5"});
  CHECK(r.code == 0);
  CHECK_THAT(r.err, Contains("phedra: warning: between keyframes the file is ") &&
                        Contains("more than the tolerance 2e-05: the morph targets are capped at 250; --nodes"));
  // The node representation keeps it.
  const Run nodes = phedra_cli({"generate", presets + "/default.json", "-o", dir / "n.glb", "--cycle", "--nodes", "-q", "--tolerance", "2e-5"});
  CHECK(nodes.code == 0);
  CHECK(nodes.err.find("warning: between keyframes") == std::string::npos);
}

TEST_CASE("the shipped presets are buildable over their whole interval, with room to edit them", "[buildability][presets]") {
  // Pinned: buildable over the whole flexion interval with 600 samples a side,
  // every panel at least 0.02 from a crossed shape (shape margin), except the
  // anti-parallelogram family (self-crossing by its kind; their panels simple too
  // for the tube).
  for (const auto& entry : fs::directory_iterator(presets)) {
    if (entry.path().extension() != ".json" || entry.path().filename() == "preset.schema.json") continue;
    const std::string name = entry.path().stem().string();
    CAPTURE(name);
    const Design d = load_design(entry.path());
    BuildabilityOptions options;
#ifdef PHEDRA_SANITIZE_BUILD
    options.sweep.samples_per_side = 200;  // the code paths; the Release run pins the 600
#else
    options.sweep.samples_per_side = 600;
#endif
    options.diagnosis.hints = false;
    const BuildabilityReport r = assess_buildability(d, nullptr, options);
    if (name.rfind("anti-parallelogram", 0) == 0) {
      CHECK(!r.self_crossing_members.empty());
      CHECK(!r.buildable());
      if (name == "anti-parallelogram-tube") CHECK(r.panels_simple());
      continue;
    }
    CHECK(r.buildable());
    CHECK(r.shape_margin > 0.02);
  }
  // The README's main job: a mixed-sign open P-hedron on a curved trajectory.
  const Design d = load_design(presets + "/default.json");
  CHECK(d.kind == "open P-hedron");
  const std::vector<Sign>& signs = d.assembly.signs(0);
  CHECK(std::count(signs.begin(), signs.end(), Sign::minus) >= 2);
  CHECK(std::count(signs.begin(), signs.end(), Sign::plus) >= 2);
}

TEST_CASE("the report without the sweep, and its summaries", "[buildability]") {
  const Design d = load_design(presets + "/default.json");
  BuildabilityOptions options;
  options.sweep_motion = false;
  const BuildabilityReport r = assess_buildability(d, nullptr, options);
  CHECK(r.summary() == "every panel is simple and t* is free of collisions (the motion was not swept)");
  CHECK(!r.buildable());  // not known without the sweep
  CHECK(r.interval());
}
