// Tubes: closure over the whole flexion interval for many generated tubes of
// both kinds; anti-parallelograms that violate z0 + z2 = z1 + z3 are detected.

#include "phedra/assembly.h"
#include "phedra/assembly_check.h"
#include "phedra/errors.h"
#include "phedra/interval_check.h"
#include "phedra/preset.h"
#include "phedra/tube.h"
#include "support/random_input.h"
#include "phedra/check_report.h"

#include <catch2/catch.hpp>

#include <optional>

using namespace phedra;
using Catch::Matchers::Contains;

using phedra::test::uniform;

namespace {

/// Four heights with consecutive (cyclic) triples pairwise distinct; symmetric
/// (z3 = z0 + z2 - z1) for anti-parallelograms unless `asymmetric`.
TubeHeights random_heights(std::mt19937_64& rng, TubeType type, bool asymmetric = false) {
  while (true) {
    TubeHeights z{uniform(rng, -3, 3), uniform(rng, -3, 3), uniform(rng, -3, 3), uniform(rng, -3, 3)};
    if (type == TubeType::anti_parallelogram) z[3] = z[0] + z[2] - z[1] + (asymmetric ? uniform(rng, 0.3, 1.0) : 0.0);
    bool distinct = true;
    for (int a = 0; a < 4; ++a) {
      distinct = distinct && std::abs(z[a] - z[(a + 1) % 4]) > 0.2 && std::abs(z[a] - z[(a + 2) % 4]) > 0.2;
    }
    if (distinct) return z;
  }
}

/// A random tube whose t* is not within 1e-5 of the model size of a limit.
std::optional<PHedron> random_tube(std::mt19937_64& rng, TubeType type, int& redrawn, bool asymmetric = false) {
  int attempt = 0;
  return test::draw_phedron(
      [&] {
        test::RandomInputShape shape;
        shape.strips = 1 + static_cast<std::size_t>(uniform(rng, 0, 30));
        shape.profile_vertices = 5;
        shape.smooth = attempt++ % 2 == 0;
        ControlPolylines input = test::random_input(rng, shape);
        set_tube_profile(input, type, random_heights(rng, type, asymmetric));
        return input;
      },
      redrawn, 500);
}

}  // namespace

TEST_CASE("100+ random tubes of each kind stay closed over the whole flexion interval", "[tubes]") {
  std::mt19937_64 rng(42);
  for (TubeType type : {TubeType::parallelogram, TubeType::anti_parallelogram}) {
    int redrawn = 0;
    for (int k = 0; k < 110; ++k) {
      CAPTURE(to_string(type), k);
      const std::optional<PHedron> p = random_tube(rng, type, redrawn);
      REQUIRE(p.has_value());
      CHECK(p->closed());
      CHECK(recognise_tube(p->input()) == type);
      CHECK(p->topology().columns() == 4);
      CHECK(p->topology().faces().size() == 4 * (p->topology().rows() - 1));
      CheckOptions options;
      options.samples = 50;
      const IntervalCheckReport r = check_over_interval(*p, options);
      CAPTURE(preset_to_json(p->input()).dump(), report_json(r).dump());
      CHECK(r.closure.value <= 1e-9 * r.model_size);
      CHECK(r.planarity.value <= 1e-9 * r.model_size);
      CHECK(r.isometry.value <= 1e-9 * r.model_size);
    }
    WARN(to_string(type) << ": drawn again (rejected or t* near a limit): " << redrawn);
  }
}

TEST_CASE("anti-parallelograms violating z0 + z2 = z1 + z3 open as they flex, and are reported", "[tubes]") {
  std::mt19937_64 rng(7);
  int redrawn = 0;
  for (int k = 0; k < 30; ++k) {
    CAPTURE(k);
    const std::optional<PHedron> p = random_tube(rng, TubeType::anti_parallelogram, redrawn, true);
    REQUIRE(p.has_value());
    CHECK_THAT(tube_symmetry_warning(p->input()), Contains("z_0 + z_2 = z_1 + z_3"));
    // Closed at t* ...
    ClosureGap at_star;
    Points v(p->vertex_count());
    p->evaluate(p->t_star(), v, &at_star);
    CHECK(at_star.value <= 1e-9 * p->model_size());
    // ... but not over the interval.
    const IntervalCheckReport r = check_over_interval(*p, {});
    CHECK(r.closure.value > 1e-6 * r.model_size);
    CHECK_FALSE(r.passed());
    const AssemblyCheckReport a = check_assembly(Assembly(*p));
    CHECK_FALSE(a.passed());
    CHECK_THAT(a.warning, Contains("closed at t* only"));
  }
}

TEST_CASE("make_tube refuses an asymmetric anti-parallelogram with the numbers", "[tubes]") {
  const ControlPolylines base = load_preset(std::string(PHEDRA_PRESETS_DIR) + "/default.json");
  CHECK_THROWS_WITH(make_tube(base, TubeType::anti_parallelogram, {-1.5, 1.0, 2.2, 0.3}),
                    Contains("tube.apex_heights") && Contains("-1.5 + 2.2 = 0.7") && Contains("1 + 0.3 = 1.3"));
  const PHedron good = make_tube(base, TubeType::anti_parallelogram, {-1.5, 1.0, 2.2, -0.3});
  CHECK(good.closed());
  CHECK(tube_symmetry_warning(good.input()).empty());
  CHECK_THROWS_WITH(tube_type_from_string("hexagon", "tube.type"), Contains("expected \"parallelogram\""));
}

TEST_CASE("the asymmetric reference tube fails its check with the reference gap", "[tubes]") {
  const PHedron p(load_preset(std::string(PHEDRA_TEST_DATA_DIR) + "/cases/tube-antiparallelogram-asymmetric.json"));
  const AssemblyCheckReport r = check_assembly(Assembly(p));
  CHECK_FALSE(r.passed());
  CHECK(r.closure.value == Approx(1.144259069340053).epsilon(1e-6));
}

TEST_CASE("closed all-'+' hexagon profiles close over the interval too", "[tubes]") {
  ControlPolylines in = load_preset(std::string(PHEDRA_PRESETS_DIR) + "/default.json");
  in.apex_heights = {-1.5, 1.0, -0.5, 2.2, 0.4, 3.0, -1.5, 1.0};
  in.signs.assign(6, Sign::plus);
  const PHedron p(in);
  CHECK(p.closed());
  CHECK(p.topology().columns() == 6);
  const IntervalCheckReport r = check_over_interval(p, {});
  CHECK(r.passed());
  // An all-'-' hexagon does not close even at t*: refused.
  in.signs.assign(6, Sign::minus);
  CHECK_THROWS_WITH(PHedron(in), Contains("does not close at t*"));
}

TEST_CASE("axial tubes (every profile plane through the axis) close too", "[tubes]") {
  std::mt19937_64 rng(5);
  int checked = 0;
  for (int k = 0; k < 40; ++k) {
    ControlPolylines in;
    const std::size_t m = 3 + k % 10;
    double angle = 0;
    for (std::size_t i = 0; i <= m; ++i) {
      const double r = uniform(rng, 1.5, 3.0);
      in.trajectory.push_back(Vec3(r * std::cos(angle), r * std::sin(angle), 0.3 * i + uniform(rng, -0.05, 0.05)));
      in.directions.push_back(Vec3(std::cos(angle), std::sin(angle), 0));
      angle += uniform(rng, 0.15, 0.5);
    }
    const TubeType type = k % 2 ? TubeType::anti_parallelogram : TubeType::parallelogram;
    try {
      const PHedron p = make_tube(in, type, random_heights(rng, type));
      const FlexionInterval& f = p.flexion_interval();
      if (!test::well_inside_interval(p.t_star(), f.lower.t, f.upper.t, p.model_size())) continue;
      const IntervalCheckReport r = check_over_interval(p, {});
      CAPTURE(k, report_json(r).dump());
      CHECK(r.passed());
      ++checked;
    } catch (const InvalidInputError&) {
    }
  }
  CHECK(checked >= 20);
}
