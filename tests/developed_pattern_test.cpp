// Developable patterns (issue 7, item 2): the flat state, the non-expansion
// criterion, folding with every choice of the strips, mountain/valley creases,
// the folded preset, the crease pattern files and phedra develop.

#include "phedra/crease_pattern.h"
#include "phedra/developed_pattern.h"
#include "phedra/errors.h"
#include "phedra/phedron.h"
#include "phedra/preset.h"
#include "support/cli_run.h"
#include "phedra/files.h"
#include "phedra/developed_preset.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <random>

using namespace phedra;
using nlohmann::json;
using Catch::Matchers::Contains;
using test::phedra_cli;
namespace fs = std::filesystem;

namespace {

const std::string pattern_file = std::string(PHEDRA_PRESETS_DIR) + "/developed/flat-pattern.json";
const std::string no_flex_file = std::string(PHEDRA_TEST_DATA_DIR) + "/developed-no-flex.json";

DevelopedPattern load_pattern(const std::string& path) {
  return DevelopedPattern(developed_from_json(parse_json_text(read_text_file(path))));
}

std::vector<int> choices(std::size_t strips, unsigned bits) {
  std::vector<int> out;
  for (std::size_t i = 0; i < strips; ++i) out.push_back((bits >> i) & 1U ? -1 : 1);
  return out;
}

/// Edge and diagonal lengths of every panel, flat against folded.
double isometry_error(const DevelopedPattern& p, const Points& x) {
  const GridTopology g = p.topology();
  const std::size_t n = p.columns();
  double worst = 0.0;
  auto flat = [&](std::size_t v) { return p.flat()[v / n][v % n]; };
  for (const Quad& q : g.faces()) {
    for (int k = 0; k < 4; ++k) {
      for (int l = k + 1; l < 4; ++l) {
        worst = std::max(worst, std::abs((x[q[k]] - x[q[l]]).norm() - (flat(q[k]) - flat(q[l])).norm()));
      }
    }
  }
  return worst;
}

}  // namespace

TEST_CASE("the shipped flat pattern folds for t increasing, with every choice of the strips", "[developed]") {
  const DevelopedPattern p = load_pattern(pattern_file);
  const std::vector<FlexDirection> d = p.flex_directions();
  REQUIRE(d.size() == 2);
  CHECK(d[0].folds);
  CHECK(!d[1].folds);
  CHECK_THAT(d[1].reason, Contains("strip"));
  for (double e : d[0].expansion) CHECK(e <= 0.0);  // the paper's non-expansion criterion
  CHECK(d[0].reach > p.t_star());
  // At t* the pattern is flat; every choice folds it isometrically, each panel stays planar.
  for (unsigned bits = 0; bits < (1U << p.strips()); ++bits) {
    const std::vector<int> fold = choices(p.strips(), bits);
    const std::optional<Points> flat = p.folded(p.t_star(), fold);
    REQUIRE(flat);
    // (A bifurcation: rounding in cos(dphi) = 1 shows as its square root, ~1e-8 of the size.)
    for (const Vec3& v : *flat) CHECK(std::abs(v.y()) < 1e-6 * p.size());
    for (double f : {1e-6, 0.1, 0.5, 0.9, 1.0}) {
      const double t = p.t_star() + f * (d[0].reach - p.t_star());
      const std::optional<Points> x = p.folded(t, fold);
      CAPTURE(bits, f);
      REQUIRE(x);
      CHECK(isometry_error(p, *x) < (f < 1.0 ? 1e-11 : 1e-7) * p.size());
    }
    // Not down, not beyond the reach.
    CHECK(!p.folded(p.t_star() - 1e-3 * p.size(), fold));
    CHECK(!p.folded(d[0].reach + 1e-3 * p.size(), fold));
  }
}

TEST_CASE("one strip is flat-foldable: flat again where its motion ends", "[developed]") {
  DevelopedInput in = developed_from_json(parse_json_text(read_text_file(pattern_file)));
  in.trajectory.resize(2);
  const DevelopedPattern one(in);
  const FlexDirection up = one.flex_directions()[0];
  REQUIRE(up.folds);
  CHECK(up.flat_at_reach);
  // The shipped pattern (four strips) ends with one strip at its limit, not flat.
  CHECK(!load_pattern(pattern_file).flex_directions()[0].flat_at_reach);
}

TEST_CASE("the folded preset is an ordinary P-hedron whose motion ends flat", "[developed]") {
  const DevelopedPattern p = load_pattern(pattern_file);
  const double reach = p.flex_directions()[0].reach;
  for (unsigned bits : {0U, 5U, 15U}) {
    CAPTURE(bits);
    const PHedron folded(p.folded_preset(p.t_star() + 0.5 * (reach - p.t_star()), choices(p.strips(), bits)));
    const FlexionInterval& f = folded.flexion_interval();
    CHECK(f.lower.t == Approx(p.t_star()).margin(1e-9 * p.size()));
    CHECK(f.upper.t == Approx(reach).margin(1e-6 * p.size()));
    // At its lower limit every vertex is back in one plane through the axis (y ~ sqrt of the distance to the limit).
    for (const Vec3& v : folded.evaluate(f.lower.t)) CHECK(std::abs(v.y()) < 1e-5 * p.size());
  }
}

TEST_CASE("crease assignments: mirrored choices swap every mountain and valley, FOLD and SVG", "[developed]") {
  const DevelopedPattern p = load_pattern(pattern_file);
  const double reach = p.flex_directions()[0].reach, t = p.t_star() + 0.5 * (reach - p.t_star());
  const double near = p.t_star() + 1e-4 * (reach - p.t_star());
  const std::vector<int> plus(p.strips(), 1), minus(p.strips(), -1);
  const CreasePattern a = crease_pattern(p, plus, near, t), b = crease_pattern(p, minus, near, t);
  REQUIRE(a.edges == b.edges);
  std::size_t boundary = 0;
  for (std::size_t k = 0; k < a.edges.size(); ++k) {
    CAPTURE(k);
    if (a.assignment[k] == 'B') {
      ++boundary;
      CHECK(b.assignment[k] == 'B');
      continue;
    }
    CHECK(((a.assignment[k] == 'M' && b.assignment[k] == 'V') || (a.assignment[k] == 'V' && b.assignment[k] == 'M')));
    CHECK(a.fold_angle[k] == Approx(-b.fold_angle[k]).margin(1e-9));
    // The sign at the written state agrees with the assignment made next to the flat state.
    CHECK((a.fold_angle[k] > 0) == (a.assignment[k] == 'V'));
  }
  // The boundary of an (m + 1) x n grid.
  CHECK(boundary == 2 * p.strips() + 2 * (p.columns() - 1));
  CHECK(a.mountains + a.valleys + boundary == a.edges.size());
  CHECK(a.mountains == b.valleys);
  const json fold = crease_fold(a);
  CHECK(fold["frame_classes"][0] == "creasePattern");
  CHECK(fold["edges_assignment"].size() == a.edges.size());
  CHECK(fold["vertices_coords"].size() == (p.strips() + 1) * p.columns());
  const std::string svg = crease_svg(a);
  CHECK_THAT(svg, Contains("class=\"mountain\""));
  CHECK_THAT(svg, Contains("class=\"valley\""));
  CHECK(svg.find("nan") == std::string::npos);
  // Readable without the docs: a visible title, a legend that names every line and the dots, a scale bar, in mm.
  for (const char* text : {">" /* title */, "crease pattern</text>", ">mountain fold (away from you)</text>", ">valley fold (towards you)</text>",
                           ">boundary (cut)</text>", ">the axis (x = 0)</text>", ">A0, A1, ...: the apex of each profile, on the axis</text>",
                           " model units</text>", "mm\" height=\""}) {
    CHECK_THAT(svg, Contains(text));
  }
  // To scale: every crease is its length in the pattern times --scale (mm).
  const CreaseDrawing drawing = crease_drawing(a, 12.5);
  CHECK(drawing.scale == 12.5);
  std::size_t k = 0;
  for (const SheetLine& line : drawing.page.lines) {
    if (line.style == LineStyle::axis || k >= a.edges.size()) continue;
    const Vec2 u = a.vertices[a.edges[k][0]], v = a.vertices[a.edges[k][1]];
    CHECK((line.b - line.a).norm() == Approx(12.5 * (v - u).norm()).margin(1e-9));
    ++k;
  }
  CHECK(k == a.edges.size());
  CHECK_THROWS_WITH(crease_drawing(a, 0.0), Contains("--scale: must be a positive number of millimetres per model unit"));
  const std::string pdf = crease_pdf(a);
  CHECK(pdf.rfind("%PDF-", 0) == 0);
}

TEST_CASE("random patterns: the exact test agrees with the motion, the criterion with the exact test", "[developed]") {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int folding = 0, stuck = 0;
  for (int k = 0; k < 60; ++k) {
    DevelopedInput in;
    for (int i = 0; i < 4; ++i) in.trajectory.emplace_back(3.0 + 0.8 * u(rng), i + 0.4 * u(rng));
    for (int j = 0; j < 5; ++j) in.apex_heights.push_back(4.0 * u(rng));
    in.signs = {Sign::plus, k % 2 ? Sign::minus : Sign::plus, Sign::plus};
    std::optional<DevelopedPattern> p;
    try {
      p.emplace(in);
    } catch (const InvalidInputError&) {
      continue;
    }
    for (const FlexDirection& f : p->flex_directions()) {
      CAPTURE(k, f.direction);
      const std::optional<Points> x = p->folded(p->t_star() + f.direction * 1e-5 * p->size(), std::vector<int>(3, 1));
      CHECK(f.folds == x.has_value());
      // Where the first-order criterion is clear, it agrees with the exact test.
      for (std::size_t i = 0; i < f.expansion.size(); ++i) {
        if (std::abs(f.expansion[i]) > 1e-6) CHECK(f.strip_folds[i] == (f.expansion[i] < 0.0));
      }
      (f.folds ? folding : stuck) += 1;
    }
  }
  CHECK(folding > 5);
  CHECK(stuck > 5);
}

TEST_CASE("phedra develop: files, no flex, and one error per bad input", "[developed][cli]") {
  const fs::path dir = fs::temp_directory_path() / ("phedra-develop-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  // +-+- turns two creases past the fully folded state before half the motion:
  // refused, creases named, nothing written, the consistent fraction said.
  const auto through = phedra_cli({"develop", pattern_file, "--fold", "+-+-", "-o", (dir / "t.fold").string()});
  CHECK(through.code == 1);
  CHECK_THAT(through.err, Contains("creases 16 (M, ") && Contains("23 (V, ") &&
                              Contains("turn past the fully folded state (+-180 deg) before fraction 0.5") &&
                              Contains("Nothing written. The motion is consistent up to fraction 0.334"));
  CHECK(!fs::exists(dir / "t.fold"));
  const auto run = phedra_cli({"develop", pattern_file, "--fold", "+-+-", "--fraction", "0.3", "-o",
                               (dir / "c.svg").string(), "-o", (dir / "c.fold").string(), "-o",
                               (dir / "folded.json").string()});
  REQUIRE(run.code == 0);
  CHECK_THAT(run.out, Contains("t increasing: folds"));
  CHECK_THAT(run.out, Contains("mountain and"));
  // The folded preset works with the other commands. With these strip choices
  // panels pass through each other: develop warns, check fails on buildability alone.
  CHECK_THAT(run.err, Contains("warning: the folded P-hedron (strip choices +-+-) is not buildable"));
  CHECK(phedra_cli({"check", (dir / "folded.json").string(), "--geometry-only"}).code == 0);
  const auto folded_check = phedra_cli({"check", (dir / "folded.json").string()});
  CHECK(folded_check.code == 1);
  CHECK_THAT(folded_check.out, Contains("intersects itself"));
  // The default choice (++++) folds without collision.
  const auto plain = phedra_cli({"develop", pattern_file, "-o", (dir / "plain.json").string()});
  CHECK(plain.err.find("not buildable") == std::string::npos);
  CHECK(phedra_cli({"check", (dir / "plain.json").string()}).code == 0);
  // Every written crease's fold angle has its assignment's sign (F: exactly 0).
  std::ifstream in(dir / "c.fold");
  const json creases = json::parse(in);
  CHECK(creases["edges_assignment"].size() > 0);
  for (std::size_t e = 0; e < creases["edges_assignment"].size(); ++e) {
    const std::string a = creases["edges_assignment"][e];
    const double angle = creases["edges_foldAngle"][e];
    if (a == "V") CHECK(angle > 0);
    if (a == "M") CHECK(angle < 0);
    if (a == "F" || a == "B") CHECK(angle == 0);
  }
  const auto j = phedra_cli({"develop", pattern_file, "--json"});
  REQUIRE(j.code == 0);
  CHECK(json::parse(j.out)["chosen_direction"] == "up");
  // No flex: exit 1, nothing written.
  const auto stuck = phedra_cli({"develop", no_flex_file, "-o", (dir / "x.svg").string()});
  CHECK(stuck.code == 1);
  CHECK_THAT(stuck.out, Contains("no real flex"));
  CHECK(!fs::exists(dir / "x.svg"));
  CHECK(phedra_cli({"develop", pattern_file, "--direction", "down"}).code == 1);
  // Bad inputs.
  const auto wrong_fold = phedra_cli({"develop", pattern_file, "--fold", "++"});
  CHECK(wrong_fold.code == 2);
  CHECK_THAT(wrong_fold.err, Contains("--fold: expected 4 signs"));
  CHECK(phedra_cli({"develop", pattern_file, "-o", (dir / "x.png").string()}).code == 2);
  auto write = [&](const json& doc) {
    std::ofstream(dir / "bad.json") << doc.dump();
    return phedra_cli({"develop", (dir / "bad.json").string()});
  };
  json on_axis = json::parse(read_text_file(pattern_file));
  on_axis["developed"]["trajectory"][2] = {0.0, 1.8};
  auto r = write(on_axis);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("developed.trajectory[2]: lies on the axis"));
  json signs = json::parse(read_text_file(pattern_file));
  signs["developed"]["signs"] = "++";
  r = write(signs);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("developed.signs: expected 3 signs"));
  json unknown = json::parse(read_text_file(pattern_file));
  unknown["developed"]["axis"] = {0, 0, 1};
  r = write(unknown);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("developed.axis: unknown key"));
  json point = json::parse(read_text_file(pattern_file));
  point["developed"]["trajectory"][1] = {1.0, 2.0, 3.0};
  r = write(point);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("developed.trajectory[1]: expected [x, z]"));
  fs::remove_all(dir);
}
