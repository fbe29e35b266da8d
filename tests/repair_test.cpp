// Repair (issue 14): random unbuildable designs (open of every sign pattern,
// parallelogram tubes, arrays) repaired, every result verified buildable by
// the buildability report itself (not by the optimizer's figures) and compared
// with its input: only the varied fields changed, every tie kept.

#include "support/test_files.h"
#include "phedra/buildability.h"
#include "phedra/errors.h"
#include "phedra/preset.h"
#include "phedra/repair.h"
#include "phedra/tube.h"
#include "support/random_input.h"
#include "phedra/design_preset.h"
#include "phedra/bench_cases.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <numbers>
#include <random>
#include <string>

using phedra::test::data;
using phedra::test::presets;
using phedra::test::read_json;

using namespace phedra;
using json = nlohmann::json;

namespace {


/// Whether `pointer` (a JSON pointer of a number) lies in a varied group.
bool may_change(const std::string& pointer, const std::vector<VariableGroup>& vary) {
  for (VariableGroup g : vary) {
    if (g == VariableGroup::apex_heights &&
        (pointer.find("heights") != std::string::npos || pointer.find("free_height") != std::string::npos)) {
      return true;
    }
    if (g == VariableGroup::directions && pointer.rfind("/directions/", 0) == 0) return true;
    if (g == VariableGroup::trajectory && pointer.rfind("/trajectory/", 0) == 0) return true;
  }
  return false;
}

/// The pointers of every number that differs (and every other difference as "!").
void differences(const json& a, const json& b, const std::string& at, std::vector<std::string>& out) {
  if (a.is_number() && b.is_number()) {
    if (a.get<double>() != b.get<double>()) out.push_back(at);
  } else if (a.is_array() && b.is_array() && a.size() == b.size()) {
    for (std::size_t k = 0; k < a.size(); ++k) differences(a[k], b[k], at + "/" + std::to_string(k), out);
  } else if (a.is_object() && b.is_object() && a.size() == b.size()) {
    for (const auto& [key, value] : a.items()) {
      if (!b.contains(key)) {
        out.push_back("!" + at + "/" + key);
      } else {
        differences(value, b[key], at + "/" + key, out);
      }
    }
  } else if (a != b) {
    out.push_back("!" + at);
  }
}

/// An unbuildable design: open P-hedra of every sign pattern, parallelogram
/// tubes, and the shipped arrays with their heights disturbed.
std::optional<json> random_unbuildable(std::mt19937_64& rng, int k) {
  const int kind = k % 5;  // 0-2 open, 3 parallelogram tube, 4 array
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  if (kind == 4) {
    static const char* arrays[] = {"grid-3x3", "row-of-cells", "edge-sharing-pair", "merged-tube"};
    json p = read_json(presets + "/" + arrays[(k / 5) % 4] + ".json");
    auto disturb = [&](json& list) {
      for (json& h : list) h = h.get<double>() + 0.6 * unit(rng);
    };
    if (p.contains("tube")) disturb(p["tube"]["apex_heights"]);
    if (p.contains("grid")) {
      disturb(p["grid"]["u_heights"]);
      disturb(p["grid"]["w_heights"]);
    }
    if (p.contains("row")) disturb(p["row"]["free_heights"]);
    if (p.contains("couplings")) {
      for (json& c : p["couplings"]) {
        if (c.contains("free_heights")) disturb(c["free_heights"]);
        if (c.contains("free_height")) c["free_height"] = c["free_height"].get<double>() + 0.6 * unit(rng);
      }
    }
    return p;
  }
  test::RandomInputShape shape;
  shape.strips = 4 + k % 6;
  shape.profile_vertices = kind <= 2 ? 4 + k % 3 : 5;
  shape.smooth = true;
  shape.random_placement = k % 3 == 0;
  int redrawn = 0;
  std::uniform_real_distribution<double> height(-3.0, 3.0);
  const std::optional<PHedron> p = test::draw_phedron(
      [&] {
        ControlPolylines input = test::random_input(rng, shape);
        if (kind == 3) {
          TubeHeights z;
          do {
            z = {height(rng), height(rng), height(rng), height(rng)};
          } while (std::abs(z[0] - z[1]) < 0.3 || std::abs(z[1] - z[2]) < 0.3 || std::abs(z[2] - z[3]) < 0.3 ||
                   std::abs(z[3] - z[0]) < 0.3);
          set_tube_profile(input, TubeType::parallelogram, z);
        }
        return input;
      },
      redrawn);
  if (!p) return std::nullopt;
  return preset_to_json(p->input());
}

/// A buildable shipped preset with its heights and directions disturbed, as a
/// user's edit may leave it (heights by up to `reach` of the model size,
/// directions turned by up to 10 degrees about the axis).
json disturbed_preset(std::mt19937_64& rng, int k) {
  static const char* names[] = {"default", "all-plus", "all-minus", "tilted-axis", "helix-tube", "parallelogram-tube",
                                "grid-3x3", "row-of-cells", "edge-sharing-pair", "merged-tube"};
  json p = read_json(presets + "/" + names[k % 10] + ".json");
  const double size = design_from_json(p).assembly.model_size();
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double reach = 0.02 + 0.08 * std::abs(unit(rng));
  auto disturb = [&](json& value) { value = value.get<double>() + reach * size * unit(rng); };
  std::function<void(json&, const std::string&)> walk = [&](json& node, const std::string& key) {
    if (node.is_number() && (key.find("heights") != std::string::npos || key == "free_height")) {
      disturb(node);
    } else if (node.is_array() || node.is_object()) {
      for (auto it = node.begin(); it != node.end(); ++it) walk(*it, node.is_object() ? it.key() : key);
    }
  };
  walk(p, "");
  if (!p.contains("axis") && p.contains("directions") && p["directions"].is_array()) {
    for (json& d : p["directions"]) {
      const double turn = 10.0 * std::numbers::pi / 180.0 * unit(rng);  // about z, the axis
      const double x = d[0].get<double>(), y = d[1].get<double>();
      d = json::array({std::cos(turn) * x - std::sin(turn) * y, std::sin(turn) * x + std::cos(turn) * y, d[2]});
    }
  }
  return p;
}

std::size_t env_count(const char* name, std::size_t fallback) {
  const char* v = std::getenv(name);
  return v ? static_cast<std::size_t>(std::atoi(v)) : fallback;
}

bool long_tests() {
  const char* v = std::getenv("PHEDRA_LONG_TESTS");
  return v && std::string(v) == "1";
}

/// What a batch of repairs achieved.
struct Tally {
  std::size_t tried = 0, repaired = 0, escalated = 0, shapes_failed = 0, motion_failed = 0;
  double seconds = 0.0, worst = 0.0;
};

/// Repairs `wanted` unbuildable designs from `draw` (within the test's time
/// budget a design), verifies every result by the buildability report at the
/// default sweep (not the repair's own figures) and compares it with its input.
Tally repair_batch(const std::function<std::optional<json>(int)>& draw, std::size_t wanted) {
  // Bounded by evaluations, not by time: the same results on any machine. The
  // long run (PHEDRA_LONG_TESTS=1) searches as `phedra repair` does by default;
  // the short one (CI) with fewer restarts and motion evaluations.
  RepairOptions options;
  options.max_seconds = 1e9;
  if (!long_tests()) {
    options.restarts = env_count("PHEDRA_REPAIR_RESTARTS", 10);
    options.motion_evaluations = env_count("PHEDRA_REPAIR_MOTION_EVALUATIONS", 100);
    options.shape_candidates = 2;
  }
  Tally tally;
  for (int k = 0; tally.tried < wanted && k < 20 * static_cast<int>(wanted); ++k) {
    const std::optional<json> preset = draw(k);
    if (!preset) continue;
    RepairResult r;
    try {
      r = repair(*preset, options);
    } catch (const InvalidInputError&) {
      continue;  // a disturbed design that no longer builds at all
    }
    if (r.already_buildable) continue;
    ++tally.tried;
    tally.seconds += r.seconds;
    tally.worst = std::max(tally.worst, r.seconds);
    CAPTURE(k, preset->dump());
    CHECK_FALSE(r.before.buildable());
    if (!r.found) {
      CHECK_FALSE(r.closest.empty());
      (r.after.panels_simple() ? tally.motion_failed : tally.shapes_failed) += 1;
      if (const char* dump = std::getenv("PHEDRA_REPAIR_DUMP")) {
        std::ofstream(std::string(dump) + "/failed-" + std::to_string(k) + ".json") << preset->dump(2);
      }
      continue;
    }
    ++tally.repaired;
    CHECK(r.fraction >= options.required_fraction - 1e-12);  // a narrower part is never a result
    const Design d = design_from_json(r.preset);
    const BuildabilityReport check = assess_buildability(d);
    CHECK(check.panels_simple());
    REQUIRE(check.interval());
    const double t = check.t_star;
    const double below = (t - check.t_lambda) * r.fraction, above = (check.t_mu - t) * r.fraction;
    CHECK(check.buildable_over(t - below * (1.0 - 1e-9), t + above * (1.0 - 1e-9)));
    // Only the varied fields changed (the trajectory only after an escalation,
    // said so), and the result is the same kind of design.
    CHECK(r.escalated == (r.varied.size() > options.vary.size()));
    if (r.escalated) {
      ++tally.escalated;
      CHECK(r.varied.back() == VariableGroup::trajectory);
      CHECK_FALSE(r.notes.empty());
    }
    std::vector<std::string> changed;
    differences(*preset, r.preset, "", changed);
    for (const std::string& pointer : changed) {
      CAPTURE(pointer);
      CHECK(may_change(pointer, r.varied));
    }
    CHECK(d.assembly.member_count() == design_from_json(*preset).assembly.member_count());
    CHECK(r.changes.size() <= changed.size());
    CHECK(r.distance > 0.0);
  }
  WARN("repaired " << tally.repaired << " of " << tally.tried << " (" << tally.escalated
                   << " varying the trajectory too); not repaired: "
                   << tally.shapes_failed << " with panels not simple, " << tally.motion_failed << " colliding; mean "
                   << tally.seconds / std::max<std::size_t>(tally.tried, 1) << " s, worst " << tally.worst << " s");
  CHECK(tally.tried >= wanted);
  return tally;
}

/// Designs a batch: PHEDRA_REPAIR_DESIGNS when set; 200 with PHEDRA_LONG_TESTS=1
/// (the success rates docs/design.md reports); 1 under the sanitizers (ASan
/// makes a sweep about 10x slower: the code paths, not the rate); else 12 (the
/// README's test command, CI).
std::size_t designs_a_batch() {
  if (const char* n = std::getenv("PHEDRA_REPAIR_DESIGNS")) return static_cast<std::size_t>(std::atoi(n));
  if (long_tests()) return 200;
#ifdef PHEDRA_SANITIZE_BUILD
  return 1;
#else
  return 8;  // 24 took over two minutes of the Release run's test time, 12 about a minute on CI
#endif
}

}  // namespace

TEST_CASE("repair: disturbed shipped presets (a user's edit gone wrong) become buildable, verified, only the varied "
          "fields change",
          "[repair]") {
  std::mt19937_64 rng(20261202);
  const Tally t = repair_batch([&](int k) { return std::optional<json>(disturbed_preset(rng, k)); },
                               designs_a_batch());
  CHECK(t.repaired * 10 >= t.tried * 7);
}

TEST_CASE("repair: random unbuildable designs (open of every sign pattern, parallelogram tubes, arrays), verified, "
          "only the varied fields change",
          "[repair]") {
  std::mt19937_64 rng(20261203);
  [[maybe_unused]] const Tally t = repair_batch([&](int k) { return random_unbuildable(rng, k); },
                                                designs_a_batch());  // checked outside the sanitizers' build
  // Measured (docs/design.md): 30 of the first 30 with the short budget, 190 of
  // 200 with the defaults; a regression shows well before these floors.
#ifndef PHEDRA_SANITIZE_BUILD
  CHECK(t.repaired * 100 >= t.tried * (long_tests() ? 85 : 70));
#endif
}

TEST_CASE("repair --objective fields: fewer fields changed than the nearest design, verified", "[repair]") {
  // A design that cuts through itself at t* (the nearest design changes 15
  // fields with phedra repair's defaults) and the bench's helical design with a
  // height moved too far (a column of bow-ties: one field does it).
  [[maybe_unused]] int fewer = 0;  // checked outside the sanitizers' build
#ifdef PHEDRA_SANITIZE_BUILD
  const std::vector<std::string> files{std::string()};  // the code paths (a sweep is about 10x slower there)
#else
  const std::vector<std::string> files{data + "/self-intersecting.json", std::string()};
#endif
  for (const std::string& file : files) {
    const json preset = file.empty() ? bench::unbuildable_open_preset(20) : read_json(file);
    RepairOptions options;
    options.max_seconds = 1e9;
    options.restarts = 10;
    options.motion_evaluations = 100;
    const RepairResult nearest = repair(preset, options);
    REQUIRE(nearest.found);
    CHECK(nearest.nearest_changes == nearest.changes.size());
    options.objective = RepairObjective::fields;
    const RepairResult sparse = repair(preset, options);
    REQUIRE(sparse.found);
    CAPTURE(file, nearest.changes.size(), sparse.changes.size());
    CHECK(sparse.nearest_changes == nearest.changes.size());
    CHECK(sparse.changes.size() <= nearest.changes.size());
    CHECK(sparse.fraction >= nearest.fraction - 1e-12);
    fewer += sparse.changes.size() < nearest.changes.size() ? 1 : 0;
    WARN((file.empty() ? "helix-20" : file) << ": the nearest design changes " << nearest.changes.size() << " fields, --objective fields " << sparse.changes.size());
    // Verified by the report, not by the search; only fields the nearest design changed may change.
    const BuildabilityReport check = assess_buildability(design_from_json(sparse.preset));
    CHECK(check.buildable_over(check.t_star, check.t_star));
    CHECK(buildable_fraction(check) >= sparse.fraction - 1e-9);
    for (const FieldChange& c : sparse.changes) {
      const bool also = std::any_of(nearest.changes.begin(), nearest.changes.end(),
                                    [&](const FieldChange& n) { return n.field == c.field; });
      CHECK(also);
    }
    if (nearest.changes.size() > 1) {
      REQUIRE_FALSE(sparse.notes.empty());
      CHECK_THAT(sparse.notes.back(), Catch::Matchers::Contains("--objective fields: "));
    }
  }
#ifndef PHEDRA_SANITIZE_BUILD
  CHECK(fewer >= 1);
#endif
}

TEST_CASE("repair: a design buildable over part of the interval is never a result, and the closest says how much", "[repair]") {
  // The heights alone, one start, no widest-part search: the fixture stays buildable
  // over 57 % of its interval (a hinge folds through above t = 0.3133), short of the whole.
  const json preset = read_json(data + "/partly-buildable.json");
  RepairOptions options;
  options.vary = {VariableGroup::apex_heights};
  options.escalate = false;
  options.search_widest = false;
  options.restarts = 0;
  options.retries = 0;
  options.motion_evaluations = 20;
  options.max_seconds = 1e9;
  const RepairResult r = repair(preset, options);
  REQUIRE_FALSE(r.found);
  CHECK(r.preset.is_null());
  CHECK(r.changes.empty());
  CHECK(r.closest_fraction > 0.5);
  CHECK(r.closest_fraction < 1.0);
  REQUIRE(r.closest_preset.is_object());
  // What the closest claims, the report of its own says.
  const BuildabilityReport check = assess_buildability(design_from_json(r.closest_preset));
  CHECK_FALSE(check.buildable());
  CHECK(buildable_fraction(check) >= r.closest_fraction - 1e-9);
  CHECK_THAT(r.closest, Catch::Matchers::Contains("buildable over"));
}
