// Agreement with the reference cases of ../shared/cases (copied to
// tests/data/cases): an independent implementation of MATH.md.

#include "phedra/phedron.h"
#include "phedra/preset.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

using namespace phedra;
using nlohmann::json;

namespace {

json load_case(const std::string& name) {
  std::ifstream in(std::filesystem::path(PHEDRA_TEST_DATA_DIR) / "cases" / (name + ".json"));
  return json::parse(in);
}

}  // namespace

TEST_CASE("reference cases: t*, case, interval and positions (open P-hedra and tubes)", "[reference]") {
  for (const std::string name : {"open-all-plus", "open-all-minus", "open-mixed-tilted-axis", "tube-parallelogram",
                                 "tube-antiparallelogram", "tube-antiparallelogram-asymmetric"}) {
    CAPTURE(name);
    const json c = load_case(name);
    const PHedron p(preset_from_json(c["preset"]));
    const json& e = c["expected"];
    const double size = p.model_size();
    const double scale = std::max(1.0, std::abs(e["t_star"].get<double>()));
    CHECK(p.t_star() == Approx(e["t_star"].get<double>()).margin(1e-12 * scale));
    CHECK(std::string(to_string(p.motion_case())) == e["case"].get<std::string>());
    CHECK(p.closed() == e["closed"].get<bool>());
    const double lo = e["flexion_interval"][0], hi = e["flexion_interval"][1];
    CHECK(std::abs(p.flexion_interval().lower.t - lo) <= 1e-9 * size);
    CHECK(std::abs(p.flexion_interval().upper.t - hi) <= 1e-9 * size);
    for (const json& sample : e["samples"]) {
      const double t = sample["t"];
      CAPTURE(t);
      const Points v = p.evaluate(t);
      const auto& grid = sample["grid"];
      REQUIRE(grid.size() == p.topology().rows());
      double worst = 0;
      for (std::size_t i = 0; i < grid.size(); ++i) {
        REQUIRE(grid[i].size() == p.topology().columns());
        for (std::size_t col = 0; col < grid[i].size(); ++col) {
          const Vec3 expected(grid[i][col][0], grid[i][col][1], grid[i][col][2]);
          worst = std::max(worst, (v[p.topology().index(i, col)] - expected).norm());
        }
      }
      // The asymmetric anti-parallelogram opens as it flexes: its expected positions
      // are those of the open chain V_{i,0..3}, which stay exact.
      CHECK(worst <= 1e-9 * size);
    }
    if (p.closed()) {
      // Largest closure gap over 101 samples of the interval, as in the reference.
      double gap = 0;
      Points v(p.vertex_count());
      for (int k = 0; k <= 100; ++k) {
        ClosureGap g;
        p.evaluate(p.t_at_fraction(k / 100.0), v, &g);
        gap = std::max(gap, g.value);
      }
      const double expected = e["max_closure_gap"];
      if (expected > 1e-6 * size) {
        CHECK(gap == Approx(expected).epsilon(1e-6));
      } else {
        CHECK(gap <= 1e-9 * size);
      }
    }
  }
}

TEST_CASE("every reference case loads unchanged, t*, case and interval ends agree (tubes too)", "[reference]") {
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(PHEDRA_TEST_DATA_DIR) / "cases")) {
    if (entry.path().extension() != ".json") continue;
    CAPTURE(entry.path().filename().string());
    const json c = load_case(entry.path().stem().string());
    const PHedron p(preset_from_json(c["preset"]));
    const json& e = c["expected"];
    CHECK(p.t_star() == e["t_star"].get<double>());
    CHECK(std::string(to_string(p.motion_case())) == e["case"].get<std::string>());
    const double lo = e["flexion_interval"][0], hi = e["flexion_interval"][1];
    CHECK(std::abs(p.flexion_interval().lower.t - lo) <= 1e-12 * std::max(1.0, std::abs(lo)));
    CHECK(std::abs(p.flexion_interval().upper.t - hi) <= 1e-12 * std::max(1.0, std::abs(hi)));
  }
}
