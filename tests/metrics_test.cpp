// Metamaterial figures (issue 7, item 4): enclosed volume, extents, deployment
// and Poisson's ratios, and phedra metrics.

#include "support/test_files.h"
#include "support/cli_run.h"
#include "phedra/metamaterial_metrics.h"
#include "phedra/plot_axes.h"
#include "phedra/tube.h"
#include "support/random_input.h"
#include "phedra/design_preset.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

using phedra::test::presets;

using namespace phedra;
using test::phedra_cli;
using test::Run;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {


std::string read(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("enclosed_volume of a square prism, either orientation, anywhere", "[metrics]") {
  const GridTopology g(3, 4, true);
  Points x;
  for (double z : {0.0, 1.0, 2.5}) {
    for (const auto& [a, b] : {std::pair{0.0, 0.0}, {2.0, 0.0}, {2.0, 3.0}, {0.0, 3.0}}) x.push_back(Vec3(a, b, z));
  }
  CHECK(enclosed_volume(g, x) == Approx(15.0));
  Points mirrored = x;
  for (Vec3& p : mirrored) p.x() = -p.x() + 7.0;  // reverses the orientation
  CHECK(enclosed_volume(g, mirrored) == Approx(15.0));
  CHECK(enclosed_volume(GridTopology(3, 4, false), x) == 0.0);
}

TEST_CASE("tube volumes do not change under translation (the end profiles close the surface)", "[metrics]") {
  std::mt19937_64 rng(11);
  int redrawn = 0;
  for (int k = 0; k < 20; ++k) {
    test::RandomInputShape shape;
    shape.strips = 1 + k % 6;
    shape.profile_vertices = 5;
    shape.smooth = true;
    const std::optional<PHedron> p = test::draw_phedron(
        [&] {
          ControlPolylines input = test::random_input(rng, shape);
          set_tube_profile(input, TubeType::parallelogram, {-1.5, 1.0, -0.5, 2.2});
          return input;
        },
        redrawn);
    REQUIRE(p);
    for (double f : {0.0, 0.3, 1.0}) {
      const Points x = p->evaluate(p->t_at_fraction(f));
      const double v = enclosed_volume(p->topology(), x);
      Points moved = x;
      for (Vec3& q : moved) q += Vec3(3.0, -7.0, 11.0);
      CAPTURE(k, f);
      CHECK(v >= 0.0);
      Vec3 lo = x[0], hi = x[0];
      for (const Vec3& q : x) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
      const double size = (hi - lo).norm();
      CHECK(enclosed_volume(p->topology(), moved) == Approx(v).epsilon(1e-9).margin(1e-12 * size * size * size));
    }
  }
}

TEST_CASE("metamaterial_metrics of the shipped tubes and arrays", "[metrics]") {
  for (const char* name : {"parallelogram-tube", "grid-3x3", "row-of-cells", "merged-tube", "default"}) {
    CAPTURE(name);
    const Design design = load_design(presets + "/" + name + ".json");
    const MetricsReport r = metamaterial_metrics(design, {.samples = 21});
    CHECK(r.samples.size() >= 21);
    CHECK(r.samples.front().t == r.t_lambda);
    CHECK(r.samples.back().t == r.t_mu);
    CHECK(r.at_t_star.t == r.t_star);
    // Principal directions: orthonormal, largest spread first.
    for (int a = 0; a < 3; ++a) {
      CHECK(r.directions[a].norm() == Approx(1.0));
      for (int b = a + 1; b < 3; ++b) CHECK(std::abs(r.directions[a].dot(r.directions[b])) < 1e-9);
    }
    CHECK(r.at_t_star.extent[0] >= r.at_t_star.extent[2]);
    for (int k = 0; k < 3; ++k) CHECK(r.extent_deployment[k] >= 1.0);
    const bool tubes = design.assembly.closed(0);
    CHECK(r.at_t_star.volume.has_value() == tubes);
    if (tubes) {
      // The array's volume is the sum of its tubes'.
      double sum = 0.0;
      for (const auto& v : r.at_t_star.member_volume) sum += v.value();
      CHECK(*r.at_t_star.volume == Approx(sum));
      CHECK(*r.volume_deployment >= 1.0);
    }
    // Poisson's ratio nu_12 at t*, against differences of independently evaluated extents.
    if (r.at_t_star.poisson[0]) {
      const double h = 1e-4 * (r.t_mu - r.t_lambda);
      auto extent = [&](double t, int k) {
        const AssemblyConfiguration c = design.assembly.evaluate(t);
        double lo = 1e300, hi = -1e300;
        for (const Points& m : c.members) {
          for (const Vec3& p : m) {
            lo = std::min(lo, r.directions[k].dot(p));
            hi = std::max(hi, r.directions[k].dot(p));
          }
        }
        return hi - lo;
      };
      const double e1 = (extent(r.t_star + h, 0) - extent(r.t_star - h, 0)) / extent(r.t_star, 0);
      const double e2 = (extent(r.t_star + h, 1) - extent(r.t_star - h, 1)) / extent(r.t_star, 1);
      CHECK(*r.at_t_star.poisson[0] == Approx(-e2 / e1).epsilon(1e-3));
    }
  }
}

TEST_CASE("phedra metrics writes CSV, JSON and SVG, and a bad format writes nothing", "[metrics][cli]") {
  const fs::path dir = fs::temp_directory_path() / ("phedra-metrics-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string grid = presets + "/grid-3x3.json";
  const Run run = phedra_cli({"metrics", grid, "--samples", "11", "-o", (dir / "m.csv").string(), "-o",
                              (dir / "m.json").string(), "-o", (dir / "m.svg").string()});
  REQUIRE(run.code == 0);
  CHECK_THAT(run.out, Contains("enclosed volume at t*:"));
  CHECK_THAT(run.out, Contains("Poisson's ratios at t*:"));
  const std::string csv = read(dir / "m.csv");
  CHECK(csv.rfind("t,extent_1,extent_2,extent_3,volume,nu_12,nu_13,nu_23,volume_member_0", 0) == 0);
  CHECK(std::count(csv.begin(), csv.end(), '\n') == 13);  // header, 11 samples, t*
  CHECK(csv.find("nan") == std::string::npos);
  const nlohmann::json j = nlohmann::json::parse(read(dir / "m.json"));
  CHECK(j["samples"].size() == 12);
  CHECK(j["principal_directions"].size() == 3);
  CHECK(j["at_t_star"]["volume"].get<double>() > 0.0);
  const std::string svg = read(dir / "m.svg");
  CHECK_THAT(svg, Contains("<svg"));
  CHECK(std::count(svg.begin(), svg.end(), 'p') > 0);
  CHECK_THAT(svg, Contains("<polyline"));
  CHECK(svg.find("nan") == std::string::npos);
  const Run bad = phedra_cli({"metrics", grid, "-o", (dir / "a.csv").string(), "-o", (dir / "b.png").string()});
  CHECK(bad.code == 2);
  CHECK_THAT(bad.err, Contains("unknown format \".png\""));
  CHECK(!fs::exists(dir / "a.csv"));
  const Run open = phedra_cli({"metrics", presets + "/default.json", "--json"});
  REQUIRE(open.code == 0);
  CHECK(nlohmann::json::parse(open.out)["at_t_star"]["volume"].is_null());
  CHECK(phedra_cli({"metrics", grid, "--samples", "1"}).code == 2);
  fs::remove_all(dir);
}

namespace {

/// The texts of elements of one class in an SVG, in order.
std::vector<std::string> texts_of_class(const std::string& svg, const std::string& cls) {
  std::vector<std::string> out;
  const std::string key = "class=\"" + cls + "\"";
  for (std::size_t at = svg.find(key); at != std::string::npos; at = svg.find(key, at + 1)) {
    const std::size_t open = svg.find('>', at) + 1, close = svg.find('<', open);
    out.push_back(svg.substr(open, close - open));
  }
  return out;
}

/// Ticks are consecutive multiples of one step of 1, 2 or 5 times a power of ten.
void check_round_ticks(const std::vector<std::string>& labels) {
  REQUIRE(labels.size() >= 2);
  std::vector<double> v;
  for (const std::string& l : labels) v.push_back(std::stod(l));
  const double step = v[1] - v[0];
  REQUIRE(step > 0.0);
  const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
  CHECK((std::abs(mantissa - 1.0) < 1e-6 || std::abs(mantissa - 2.0) < 1e-6 || std::abs(mantissa - 5.0) < 1e-6));
  for (std::size_t k = 0; k < v.size(); ++k) {
    CHECK(v[k] / step == Approx(std::round(v[k] / step)).margin(1e-6));
    if (k > 0) CHECK(v[k] - v[k - 1] == Approx(step).epsilon(1e-6));
    CHECK(labels[k].size() <= 12);  // no rounding noise: 0.30000000000000004
  }
}

}  // namespace

TEST_CASE("round ticks: 1-2-5 steps, labels without noise, ranges ending on ticks", "[metrics][plots]") {
  const Ticks t = round_ticks(0.827, 1.135);  // the old plot's ticks: 0.827, 0.981, 1.135
  CHECK(t.step == Approx(0.1));
  CHECK(t.labels == std::vector<std::string>{"0.9", "1.0", "1.1"});
  CHECK(round_ticks(-10.0, 10.0).labels == std::vector<std::string>{"-10", "-5", "0", "5", "10"});
  CHECK(round_ticks(0.0, 0.3, 6).labels == std::vector<std::string>{"0", "0.05", "0.10", "0.15", "0.20", "0.25", "0.30"});
  const auto range = round_range(3.632, 4.85);  // the old plot's 3.632 .. 4.85
  CHECK(range.first == Approx(3.5));
  CHECK(range.second == Approx(5.0));
  CHECK(tick_label(-1e-17, 0.1) == "0");
  CHECK(tick_label(8e6, 2e6) == "8e+06");
  for (double lo : {-3.7, 0.0, 0.001, 17.0, -1234.5}) {
    for (double span : {1e-3, 0.07, 1.0, 42.0, 5e4}) {
      CAPTURE(lo, span);
      check_round_ticks(round_ticks(lo, lo + span).labels);
    }
  }
}

TEST_CASE("metrics plots: axes with units and round ticks, the interval's share, clipping and non-buildable parts shown", "[metrics][plots][cli]") {
  const fs::path dir = fs::temp_directory_path() / ("phedra-plots-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  REQUIRE(phedra_cli({"metrics", presets + "/grid-3x3.json", "-o", (dir / "g.svg").string()}).code == 0);
  const std::string svg = read(dir / "g.svg");
  const std::vector<std::string> y = texts_of_class(svg, "y-tick"), x = texts_of_class(svg, "x-tick");
  // Two plots: each with its own y ticks and the same t ticks.
  CHECK(texts_of_class(svg, "y-label") ==
        std::vector<std::string>{"ratio to the value at t* (dimensionless)", "Poisson's ratio (dimensionless)"});
  CHECK(texts_of_class(svg, "x-label").size() == 2);
  CHECK_THAT(texts_of_class(svg, "x-label")[0], Contains("t: height of the moving apex (model units)"));
  CHECK(texts_of_class(svg, "fraction-tick") ==
        std::vector<std::string>{"0 %", "25 %", "50 %", "75 %", "100 %", "0 %", "25 %", "50 %", "75 %", "100 %"});
  REQUIRE(x.size() % 2 == 0);
  check_round_ticks(std::vector<std::string>(x.begin(), x.begin() + static_cast<long>(x.size() / 2)));
  // The Poisson plot of grid-3x3 is clipped: its axis stops at +-10, the clipping is stated and marked.
  const std::size_t split = svg.find("Effective Poisson");
  const std::vector<std::string> y1 = texts_of_class(svg.substr(0, split), "y-tick"),
                                 y2 = texts_of_class(svg.substr(split), "y-tick");
  check_round_ticks(y1);
  check_round_ticks(y2);
  CHECK(y2.front() == "-10");
  CHECK(y2.back() == "10");
  CHECK(texts_of_class(svg, "clip-note").size() == 1);
  CHECK_THAT(svg, Contains("class=\"clipped\""));
  CHECK(svg.find("not-buildable") == std::string::npos);  // buildable over the whole interval
  // A design buildable over part of its interval: the rest shaded, in both plots, and in the legend.
  REQUIRE(phedra_cli({"metrics", std::string(PHEDRA_TEST_DATA_DIR) + "/partly-buildable.json", "-o", (dir / "p.svg").string()}).code == 0);
  const std::string partly = read(dir / "p.svg");
  std::size_t shaded = 0;
  for (std::size_t at = partly.find("class=\"not-buildable\""); at != std::string::npos; at = partly.find("class=\"not-buildable\"", at + 1)) ++shaded;
  CHECK(shaded == 2);
  CHECK_THAT(partly, Contains(">not buildable</text>"));
  // Unclipped data: no note, the axis fits the data.
  REQUIRE(phedra_cli({"metrics", presets + "/parallelogram-tube.json", "-o", (dir / "t.svg").string()}).code == 0);
  const std::string tube = read(dir / "t.svg");
  if (tube.find("class=\"clipped\"") == std::string::npos) CHECK(texts_of_class(tube, "clip-note").empty());
  // A volume of 0 at t* (found by the fuzzer): no ratio to it, and no NaN anywhere in the files.
  const std::string zero = std::string(PHEDRA_TEST_DATA_DIR) + "/zero-volume-at-t-star.json";
  REQUIRE(phedra_cli({"metrics", zero, "-o", (dir / "z.svg").string(), "-o", (dir / "z.csv").string(), "-o", (dir / "z.json").string()}).code == 0);
  for (const char* file : {"z.svg", "z.csv", "z.json"}) {
    const std::string text = read(dir / file);
    CAPTURE(file);
    CHECK(text.find("nan") == std::string::npos);
    CHECK(text.find("inf") == std::string::npos);
  }
  CHECK(read(dir / "z.svg").find("V / V(t*)") == std::string::npos);
  fs::remove_all(dir);
}
