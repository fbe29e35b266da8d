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

#include <algorithm>
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

namespace {

/// The test's own stretch along d from t* to t: the least-squares affine map of
/// every vertex (Eigen's QR on the n x 4 system), |F d|.
double independent_stretch(const Design& design, double t, const Vec3& d) {
  const AssemblyConfiguration star = design.assembly.evaluate(design.assembly.t_star());
  const AssemblyConfiguration now = design.assembly.evaluate(t);
  std::size_t n = 0;
  for (const Points& m : star.members) n += m.size();
  Eigen::MatrixXd a(n, 4), b(n, 3);
  std::size_t row = 0;
  for (std::size_t m = 0; m < star.members.size(); ++m) {
    for (std::size_t v = 0; v < star.members[m].size(); ++v, ++row) {
      a.row(row) << star.members[m][v].transpose(), 1.0;
      b.row(row) = now.members[m][v].transpose();
    }
  }
  const Eigen::MatrixXd solution = a.colPivHouseholderQr().solve(b);  // 4 x 3: [F^T; b^T]
  const Mat3 f = solution.topRows(3).transpose();
  return (f * d).norm();
}

}  // namespace

TEST_CASE("metamaterial_metrics of the shipped tubes and arrays", "[metrics]") {
  for (const char* name : {"parallelogram-tube", "grid-3x3", "row-of-cells", "merged-tube", "default"}) {
    CAPTURE(name);
    const Design design = load_design(presets + "/" + name + ".json");
    const MetricsReport r = metamaterial_metrics(design, {.samples = 21});
    CHECK(r.samples.size() >= 21);
    CHECK(r.samples.front().t == r.t_lambda);
    CHECK(r.samples.back().t == r.t_mu);
    CHECK(r.at_t_star.t == r.t_star);
    // The axes: orthonormal, right-handed, axis 1 along the trajectory (first profile to last).
    for (int a = 0; a < 3; ++a) {
      CHECK(r.directions[a].norm() == Approx(1.0));
      for (int b = a + 1; b < 3; ++b) CHECK(std::abs(r.directions[a].dot(r.directions[b])) < 1e-9);
    }
    CHECK(r.directions[0].cross(r.directions[1]).dot(r.directions[2]) == Approx(1.0));
    const AssemblyConfiguration star = design.assembly.evaluate(r.t_star);
    const GridTopology& g = design.assembly.topology(0);
    const Vec3 chord = star.members[0][g.index(g.rows() - 1, 0)] - star.members[0][g.index(0, 0)];
    CHECK(chord.normalized().dot(r.directions[0]) > 0.5);
    // Lengths at t* are the bounding extents then; stretch 1 there.
    for (int k = 0; k < 3; ++k) {
      REQUIRE(r.at_t_star.length[k]);
      CHECK(*r.at_t_star.length[k] == Approx(r.at_t_star.bounding_extent[k]));
      REQUIRE(r.extent_deployment[k]);
      CHECK(*r.extent_deployment[k] >= 1.0);
    }
    const bool tubes = design.assembly.closed(0);
    CHECK(r.at_t_star.volume.has_value() == tubes);
    if (tubes) {
      // The array's volume is the sum of its tubes'.
      double sum = 0.0;
      for (const auto& v : r.at_t_star.member_volume) sum += v.value();
      CHECK(*r.at_t_star.volume == Approx(sum));
      CHECK(*r.volume_deployment >= 1.0);
      CHECK(r.figure("volume_ratio") == r.volume_deployment);
    }
    // Lengths against the test's own affine fit, at every fifth sample.
    for (std::size_t s = 0; s < r.samples.size(); s += 5) {
      for (int k = 0; k < 3; ++k) {
        CHECK(*r.samples[s].length[k] ==
              Approx(*r.at_t_star.length[k] * independent_stretch(design, r.samples[s].t, r.directions[k])).epsilon(1e-9));
      }
    }
    // Poisson's ratios at t*, against central differences of the independent stretches.
    const double h = 1e-5 * (r.t_mu - r.t_lambda);
    std::array<double, 3> rate{};
    for (int k = 0; k < 3; ++k) {
      rate[k] = (std::log(independent_stretch(design, r.t_star + h, r.directions[k])) -
                 std::log(independent_stretch(design, r.t_star - h, r.directions[k]))) / (2.0 * h);
    }
    const std::array<std::pair<int, int>, 3> pairs{{{0, 1}, {0, 2}, {1, 2}}};
    for (int p = 0; p < 3; ++p) {
      REQUIRE(r.at_t_star.poisson[p]);
      CHECK(*r.at_t_star.poisson[p] == Approx(-rate[pairs[p].second] / rate[pairs[p].first]).epsilon(1e-5));
      CHECK(r.figure(figure_names()[p]) == r.at_t_star.poisson[p]);
    }
    CHECK(r.figure("flexion_width") == Approx(r.t_mu - r.t_lambda));
    CHECK_THROWS_AS(r.figure("poisson.nu_21"), InvalidInputError);
  }
}

TEST_CASE("metrics curves are continuous and their rates agree with the lengths, on random designs", "[metrics]") {
  std::mt19937_64 rng(26);
  int redrawn = 0, checked = 0;
  for (int k = 0; k < 24; ++k) {
    test::RandomInputShape shape;
    shape.strips = 2 + k % 5;
    shape.profile_vertices = 3 + k % 4;
    shape.smooth = k % 2 == 0;
    const bool tube = k % 3 == 0;
    const std::optional<PHedron> p = test::draw_phedron(
        [&] {
          ControlPolylines input = test::random_input(rng, shape);
          if (tube) set_tube_profile(input, TubeType::parallelogram, {-1.5, 1.0, -0.5, 2.2});
          return input;
        },
        redrawn);
    REQUIRE(p);
    const Design design = single_design(p->input());
    for (const MetricsAxes axes : {MetricsAxes::structural, MetricsAxes::xyz}) {
      const MetricsReport r = metamaterial_metrics(design, {.samples = 401, .axes = axes});
      CAPTURE(k, to_string(axes));
      const double width = r.t_mu - r.t_lambda;
      for (int a = 0; a < 3; ++a) {
        if (!r.at_t_star.length[a]) continue;
        // Between samples (away from the limits, where the motion's derivative blows up):
        // ln L changes as its rate says (trapezoid rule), so no jump and no corner.
        for (std::size_t s = 0; s + 1 < r.samples.size(); ++s) {
          const MetricsSample &u = r.samples[s], &v = r.samples[s + 1];
          if (u.t < r.t_lambda + 0.05 * width || v.t > r.t_mu - 0.05 * width) continue;
          const double dt = v.t - u.t;
          const double change = std::log(*v.length[a] / *u.length[a]);
          const double predicted = 0.5 * dt * (*u.strain_rate[a] + *v.strain_rate[a]);
          const double scale = std::max(std::abs(*u.strain_rate[a]), std::abs(*v.strain_rate[a])) * dt;
          CAPTURE(a, u.t, v.t, change, predicted);
          CHECK(std::abs(change - predicted) <= 0.02 * scale + 1e-12);
          ++checked;
        }
      }
      // The strain rates have no jump between samples: at each interval's midpoint
      // (evaluated on its own) a rate is near the chord of its ends, within an eighth
      // of the second difference on either side (neither straddles this interval, so
      // a jump here is not excused). Poisson's ratios are their quotients (so they are
      // continuous but at their poles, where L_j is stationary).
      const HomogenizedStrain strain(design.assembly, axes);
      const std::array<std::pair<int, int>, 3> pairs{{{0, 1}, {0, 2}, {1, 2}}};
      for (std::size_t s = 2; s + 3 < r.samples.size(); s += 3) {
        const MetricsSample &u = r.samples[s], &v = r.samples[s + 1];
        if (u.t < r.t_lambda + 0.05 * width || v.t > r.t_mu - 0.05 * width) continue;
        const HomogenizedStrain::State mid = strain.at(0.5 * (u.t + v.t));
        for (int a = 0; a < 3; ++a) {
          if (!mid.rate[a]) continue;
          auto rate = [&](std::size_t n) { return *r.samples[n].strain_rate[a]; };
          const double chord = 0.5 * (rate(s) + rate(s + 1)), step = std::abs(rate(s) - rate(s + 1));
          const double bend = std::min(std::abs(rate(s - 2) - 2.0 * rate(s - 1) + rate(s)),
                                       std::abs(rate(s + 1) - 2.0 * rate(s + 2) + rate(s + 3)));
          CAPTURE(a, u.t, rate(s), *mid.rate[a], rate(s + 1), bend);
          CHECK(std::abs(*mid.rate[a] - chord) <= 0.1 * step + 0.5 * bend + 1e-9 * (1.0 + std::abs(chord)));
          ++checked;
        }
        for (int q = 0; q < 3; ++q) {
          if (!u.poisson[q]) continue;
          CHECK(*u.poisson[q] == Approx(-*u.strain_rate[pairs[q].second] / *u.strain_rate[pairs[q].first]));
        }
      }
    }
  }
  CHECK(checked > 1000);
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
  CHECK(csv.rfind("t,length_1,length_2,length_3,bounding_extent_1,bounding_extent_2,bounding_extent_3,volume,nu_12,nu_13,"
                  "nu_23,volume_member_0", 0) == 0);
  CHECK(std::count(csv.begin(), csv.end(), '\n') == 13);  // header, 11 samples, t*
  CHECK(csv.find("nan") == std::string::npos);
  const nlohmann::json j = nlohmann::json::parse(read(dir / "m.json"));
  CHECK(j["samples"].size() == 12);
  CHECK(j["directions"].size() == 3);
  CHECK(j["axes"] == "structural");
  // The figures optimize takes, by name; the text's Poisson's ratio at t* is the JSON's (and the plot's t* sample).
  for (const std::string& name : figure_names()) CHECK(j["figures"].contains(name));
  CHECK(j["figures"]["poisson.nu_12"] == j["at_t_star"]["poisson"]["nu_12"]);
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
        std::vector<std::string>{"ratio to the value at t* (dimensionless)", "Poisson's ratio (dimensionless, symmetric log)"});
  CHECK(texts_of_class(svg, "x-label").size() == 2);
  CHECK_THAT(texts_of_class(svg, "x-label")[0], Contains("t: height of the moving apex (model units)"));
  CHECK(texts_of_class(svg, "fraction-tick") ==
        std::vector<std::string>{"0 %", "25 %", "50 %", "75 %", "100 %", "0 %", "25 %", "50 %", "75 %", "100 %"});
  REQUIRE(x.size() % 2 == 0);
  check_round_ticks(std::vector<std::string>(x.begin(), x.begin() + static_cast<long>(x.size() / 2)));
  // The Poisson plot of grid-3x3 (issue 39): on a symmetric log scale every value is on it (nu_12 and
  // nu_13 pass through infinity where L1 is stationary, nu_23 lies beyond 10 over a third of the
  // interval), the poles drawn as dashed lines, the values at the flexion limits marked apart.
  const std::size_t split = svg.find("Effective Poisson");
  const std::vector<std::string> y1 = texts_of_class(svg.substr(0, split), "y-tick"),
                                 y2 = texts_of_class(svg.substr(split), "y-tick");
  check_round_ticks(y1);
  const std::vector<std::string> linear{"-1", "0", "1"};  // +-0.5 too when the axis spans few decades
  CHECK(std::search(y2.begin(), y2.end(), linear.begin(), linear.end()) != y2.end());
  CHECK(std::find(y2.begin(), y2.end(), "10") != y2.end());
  CHECK(std::find(y2.begin(), y2.end(), "-10") != y2.end());
  CHECK(texts_of_class(svg, "clip-note").empty());
  CHECK(svg.find("class=\"clipped\"") == std::string::npos);
  CHECK(texts_of_class(svg, "scale-note").size() == 1);
  const std::string poisson_part = svg.substr(split);
  std::size_t poles = 0, limits = 0;
  for (std::size_t at = poisson_part.find("class=\"pole\""); at != std::string::npos; at = poisson_part.find("class=\"pole\"", at + 1)) ++poles;
  for (std::size_t at = poisson_part.find("class=\"limit-value\""); at != std::string::npos; at = poisson_part.find("class=\"limit-value\"", at + 1)) ++limits;
  CHECK(poles >= 1);
  CHECK(limits >= 2);
  CHECK_THAT(poisson_part, Contains("L1 stationary"));
  // The pole lies where nu_12 changes sign through infinity: near t = -1.45.
  {
    const MetricsReport m = metamaterial_metrics(load_design(presets + "/grid-3x3.json"), {});
    bool near = false;
    for (std::size_t k = 0; k + 1 < m.samples.size(); ++k) {
      const auto& a = m.samples[k].strain_rate[0];
      const auto& b = m.samples[k + 1].strain_rate[0];
      if (a && b && *a * *b < 0.0) near = near || std::abs(m.samples[k].t - (-1.45)) < 0.05;
    }
    CHECK(near);
  }
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
