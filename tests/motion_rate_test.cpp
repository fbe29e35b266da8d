// The exact rate of the motion dX/dt (Assembly::evaluate_rate): against
// high-order differences of evaluate(t), isometric (every edge keeps its length
// to first order), on every sign pattern, tubes, arrays and the shipped presets.

#include "support/random_input.h"
#include "support/test_files.h"
#include "phedra/design.h"
#include "phedra/design_preset.h"
#include "phedra/homogenized_strain.h"
#include "phedra/net_writer.h"
#include "phedra/tube.h"

#include <catch2/catch.hpp>

#include <filesystem>

using namespace phedra;

namespace {

double largest_norm(const std::vector<Points>& members) {
  double largest = 0.0;
  for (const Points& m : members)
    for (const Vec3& v : m) largest = std::max(largest, v.norm());
  return largest;
}

/// dX/dt by Richardson-extrapolated central differences (sixth order), step h.
std::vector<Points> differenced(const Assembly& a, double t, double h) {
  auto central = [&](double step) {
    const AssemblyConfiguration plus = a.evaluate(t + step), minus = a.evaluate(t - step);
    std::vector<Points> d = plus.members;
    for (std::size_t m = 0; m < d.size(); ++m)
      for (std::size_t v = 0; v < d[m].size(); ++v) d[m][v] = (plus.members[m][v] - minus.members[m][v]) / (2 * step);
    return d;
  };
  const std::vector<Points> d1 = central(h), d2 = central(h / 2), d4 = central(h / 4);
  std::vector<Points> out = d1;
  for (std::size_t m = 0; m < out.size(); ++m) {
    for (std::size_t v = 0; v < out[m].size(); ++v) {
      const Vec3 r1 = (4 * d2[m][v] - d1[m][v]) / 3, r2 = (4 * d4[m][v] - d2[m][v]) / 3;
      out[m][v] = (16 * r2 - r1) / 15;
    }
  }
  return out;
}

/// Checks the rate at t against differences and isometry; returns the worst relative difference.
double check_rate(const Design& design, double t) {
  const Assembly& a = design.assembly;
  AssemblyConfiguration c;
  std::vector<Points> rate;
  REQUIRE(a.evaluate_rate(t, c, rate));
  const AssemblyConfiguration plain = a.evaluate(t);
  double scale = largest_norm(rate);
  REQUIRE(scale > 0.0);
  for (std::size_t m = 0; m < c.members.size(); ++m) {
    for (std::size_t v = 0; v < c.members[m].size(); ++v) REQUIRE(c.members[m][v] == plain.members[m][v]);
  }
  // Every edge of every member keeps its length: (x_a - x_b) . (v_a - v_b) = 0.
  double isometry = 0.0;
  for (std::size_t m = 0; m < c.members.size(); ++m) {
    const GridTopology& g = a.topology(m);
    for (std::size_t f = 0; f < g.face_count(); ++f) {
      const Quad q = g.face(f);
      for (int k = 0; k < 4; ++k) {
        const std::size_t i = q[k], j = q[(k + 1) % 4];
        isometry = std::max(isometry, std::abs((c.members[m][i] - c.members[m][j]).dot(rate[m][i] - rate[m][j])));
      }
    }
  }
  CHECK(isometry <= 1e-11 * a.model_size() * scale);
  const double width = a.flexion_interval().upper.t - a.flexion_interval().lower.t;
  const double h = 1e-3 * std::min({width, t - a.flexion_interval().lower.t, a.flexion_interval().upper.t - t});
  const std::vector<Points> d = differenced(a, t, h);
  double worst = 0.0;
  for (std::size_t m = 0; m < d.size(); ++m)
    for (std::size_t v = 0; v < d[m].size(); ++v) worst = std::max(worst, (d[m][v] - rate[m][v]).norm() / scale);
  return worst;
}

}  // namespace

TEST_CASE("the exact rate dX/dt agrees with differences and keeps every edge length", "[rate]") {
  std::mt19937_64 rng(2026);
  int redrawn = 0, checked = 0;
  for (int k = 0; k < 24; ++k) {
    test::RandomInputShape shape;
    shape.strips = 1 + k % 6;
    shape.profile_vertices = 3 + k % 4;
    shape.smooth = k % 2 == 0;
    shape.signs = test::sign_pattern(shape.profile_vertices, static_cast<std::size_t>(k) % (1u << (shape.profile_vertices - 1)));
    const std::optional<PHedron> p = test::draw_phedron([&] { return test::random_input(rng, shape); }, redrawn);
    REQUIRE(p);
    const Design design = single_design(p->input());
    const auto& interval = design.assembly.flexion_interval();
    for (double f : {0.1, 0.5, 0.9}) {
      const double t = interval.lower.t + f * (interval.upper.t - interval.lower.t);
      CHECK(check_rate(design, t) <= 1e-7);
      ++checked;
    }
  }
  CHECK(checked == 72);
}

TEST_CASE("the exact rate of every shipped preset (tubes, arrays, couplings)", "[rate]") {
  for (const auto& entry : std::filesystem::directory_iterator(test::presets)) {
    if (entry.path().extension() != ".json" || entry.path().filename() == "preset.schema.json") continue;
    INFO(entry.path().filename().string());
    const Design design = load_design(entry.path());
    const auto& interval = design.assembly.flexion_interval();
    for (double f : {0.2, 0.5, 0.8}) {
      CHECK(check_rate(design, interval.lower.t + f * (interval.upper.t - interval.lower.t)) <= 1e-7);
    }
  }
}

TEST_CASE("the rate is infinite at a flexion limit: evaluate_rate says so", "[rate]") {
  const Design design = load_design(std::filesystem::path(test::presets) / "default.json");
  AssemblyConfiguration c;
  std::vector<Points> rate;
  CHECK_FALSE(design.assembly.evaluate_rate(design.assembly.flexion_interval().upper.t, c, rate));
  CHECK(c.members[0].size() == design.assembly.topology(0).vertex_count());
  CHECK(design.assembly.evaluate_rate(design.assembly.t_star(), c, rate));
}

TEST_CASE("vertices written from the canonical nets, and the strain read from them, equal the members written out",
          "[rate][metrics]") {
  // Assembly::write_vertices (the energy's nodes) against evaluate_rate's members, bit for bit, and
  // HomogenizedStrain from the nets against the one from the positions: every shipped preset, open and
  // closed members, every vertex, inside the interval and at a limit (no rates there).
  std::size_t shipped = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::presets)) {
    if (entry.path().extension() != ".json" || entry.path().filename() == "preset.schema.json") continue;
    INFO(entry.path().filename().string());
    const Design design = load_design(entry.path());
    const Assembly& a = design.assembly;
    std::vector<VertexRef> every;
    for (std::size_t m = 0; m < a.member_count(); ++m) {
      for (std::size_t v = 0; v < a.topology(m).vertex_count(); ++v) every.push_back({m, v});
    }
    const std::vector<Assembly::NetPlace> places = a.net_places(every);
    const HomogenizedStrain strain(a, MetricsAxes::structural);
    const auto& interval = a.flexion_interval();
    for (double f : {0.3, 0.9, 1.0}) {
      const double t = f == 1.0 ? interval.upper.t : interval.lower.t + f * (interval.upper.t - interval.lower.t);
      AssemblyConfiguration c;
      std::vector<Points> rates;
      const bool finite = a.evaluate_rate(t, c, rates);
      CHECK(finite == (f < 1.0));
      std::vector<NetState> states, state_rates;
      CHECK(a.evaluate_canonical_rate(t, states, state_rates) == finite);
      Points x, v;
      a.write_vertices(states, places, x);
      if (finite) a.write_vertices(state_rates, places, v, NetWriter::Kind::rates);
      // Without the closed members' closure columns (the energy's evaluation): the same vertices.
      std::vector<NetState> open_states, open_rates;
      CHECK(a.evaluate_canonical_rate(t, open_states, open_rates, false) == finite);
      Points x_open, v_open;
      a.write_vertices(open_states, places, x_open);
      if (finite) a.write_vertices(open_rates, places, v_open, NetWriter::Kind::rates);
      for (std::size_t k = 0; k < every.size(); ++k) {
        REQUIRE(x[k] == c.members[every[k].member][every[k].vertex]);
        REQUIRE(x_open[k] == x[k]);
        if (finite) REQUIRE(v[k] == rates[every[k].member][every[k].vertex]);
        if (finite) REQUIRE(v_open[k] == v[k]);
      }
      const HomogenizedStrain::State from_open = strain.state_of(open_states, finite ? &open_rates : nullptr);
      for (int k = 0; k < 3; ++k) {
        if (from_open.stretch[k]) CHECK(*from_open.stretch[k] == *strain.state_of(states, nullptr).stretch[k]);
      }
      const HomogenizedStrain::State written = strain.state_of(c, finite ? &rates : nullptr);
      const HomogenizedStrain::State nets = strain.state_of(states, finite ? &state_rates : nullptr);
      for (int k = 0; k < 3; ++k) {
        REQUIRE(written.stretch[k].has_value() == nets.stretch[k].has_value());
        REQUIRE(written.rate[k].has_value() == nets.rate[k].has_value());
        if (written.stretch[k]) CHECK(std::abs(*nets.stretch[k] - *written.stretch[k]) <= 1e-13 * *written.stretch[k]);
        if (written.rate[k]) CHECK(std::abs(*nets.rate[k] - *written.rate[k]) <= 1e-11 * (1.0 + std::abs(*written.rate[k])));
      }
    }
    ++shipped;
  }
  CHECK(shipped >= 8);
}
