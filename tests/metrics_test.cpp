// Metamaterial figures (issue 7, item 4): enclosed volume, extents, deployment
// and Poisson's ratios, and phedra metrics.

#include "support/cli_run.h"
#include "phedra/metamaterial_metrics.h"
#include "phedra/tube.h"
#include "support/random_input.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

using namespace phedra;
using test::phedra_cli;
using test::Run;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

const std::string presets = PHEDRA_PRESETS_DIR;

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
