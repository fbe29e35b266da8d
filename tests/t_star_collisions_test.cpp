// The collision check at t* kept between the steps of a drag (issue 24, item 3:
// analysis/t_star_collisions.h): over random drags of random designs, the shipped
// presets and the test designs, it says what the check from scratch says at
// every step (a collision or none), while it tests again only a small part of
// the pairs when the design moved little.

#include "support/random_input.h"
#include "support/test_files.h"

#include "phedra/design_preset.h"
#include "phedra/errors.h"
#include "phedra/preset.h"
#include "phedra/self_intersection.h"
#include "phedra/t_star_collisions.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <random>

using namespace phedra;
using json = nlohmann::json;
namespace fs = std::filesystem;

namespace {

json preset_file(const fs::path& path) {
  std::ifstream in(path);
  return json::parse(in);
}

/// Every number of the preset's `key` list (points or heights), by pointer.
std::vector<json::json_pointer> numbers_of(const json& preset, const std::string& key) {
  std::vector<json::json_pointer> out;
  const json::json_pointer base("/" + key);
  if (!preset.contains(base)) return out;
  const json& list = preset.at(base);
  if (!list.is_array()) return out;
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (list[i].is_array()) {
      for (std::size_t c = 0; c < list[i].size(); ++c) out.push_back(base / i / c);
    } else if (list[i].is_number()) {
      out.push_back(base / i);
    }
  }
  return out;
}

struct DragTally {
  int steps = 0, collisions = 0, kept = 0;
  std::size_t pairs = 0, tested = 0;
};

/// Drags one number of `preset` (a trajectory coordinate, a direction's, an apex
/// height) in `count` steps of random size (from a rounding error to a twentieth
/// of the model), checking each design both ways.
void drag(json preset, std::mt19937_64& rng, int count, TStarCollisions& kept, DragTally& tally) {
  std::vector<json::json_pointer> fields;
  const json::json_pointer root = preset.contains("tube") && preset["tube"].is_object() ? json::json_pointer("/tube") : json::json_pointer("");
  for (const char* key : {"trajectory", "directions", "apex_heights"}) {
    for (const json::json_pointer& p : numbers_of(preset, key)) fields.push_back(p);
  }
  if (preset.contains("tube")) {
    for (const json::json_pointer& p : numbers_of(preset["tube"], "apex_heights")) fields.push_back(json::json_pointer("/tube") / p);
  }
  REQUIRE(!fields.empty());
  const json::json_pointer field = fields[std::uniform_int_distribution<std::size_t>(0, fields.size() - 1)(rng)];
  double size = 1.0;
  try {
    size = design_from_json(preset).assembly.model_size();
  } catch (const Error&) {
    return;
  }
  const double steps[] = {1e-12, 1e-6, 1e-4, 1e-3, 1e-2, 5e-2};
  for (int k = 0; k < count; ++k) {
    const double step = steps[std::uniform_int_distribution<int>(0, 5)(rng)] * size * (rng() % 2 ? 1.0 : -1.0);
    preset.at(field) = preset.at(field).get<double>() + step;
    std::optional<Design> design;
    try {
      design.emplace(design_from_json(preset));
    } catch (const Error&) {
      preset.at(field) = preset.at(field).get<double>() - step;  // refused, as the designer does
      continue;
    }
    CAPTURE(field.to_string(), k, step);
    const bool from_scratch = self_intersection_at_t_star(*design).has_value();
    const bool incremental = kept.check(*design).has_value();
    REQUIRE(incremental == from_scratch);
    ++tally.steps;
    tally.collisions += from_scratch ? 1 : 0;
    if (!kept.last().rebuilt) {
      ++tally.kept;
      tally.pairs += kept.last().pairs;
      tally.tested += kept.last().tested;
      CHECK(kept.last().certified + kept.last().tested <= kept.last().pairs);
    }
  }
}

}  // namespace

TEST_CASE("the kept collision check at t* agrees with the check from scratch along random drags of random designs",
          "[self-intersection][keep]") {
  std::mt19937_64 rng(20261204);
  TStarCollisions kept;  // one for all: designs of other meshes follow each other too
  DragTally tally;
  int redrawn = 0;
  for (int k = 0; k < 32; ++k) {
    test::RandomInputShape shape;
    shape.strips = 4 + k % 9;
    shape.profile_vertices = 3 + k % 5;
    shape.smooth = k % 4 != 3;  // (irregular designs mostly cut through themselves)
    const std::optional<PHedron> p = test::draw_phedron([&] { return test::random_input(rng, shape); }, redrawn);
    REQUIRE(p);
    drag(preset_to_json(p->input()), rng, 12, kept, tally);
  }
  CAPTURE(tally.steps, tally.collisions, tally.kept);
  CHECK(tally.steps > 200);
  CHECK(tally.collisions > 20);                 // both answers occur
  CHECK(tally.steps - tally.collisions > 5);   // (random designs mostly cut through themselves at t*; the presets below do not)
  CHECK(tally.kept > 50);                       // and the kept list is used
}

TEST_CASE("the kept collision check at t* on the shipped presets and the test designs: arrays, tubes, a crossing design",
          "[self-intersection][keep]") {
  std::mt19937_64 rng(4);
  TStarCollisions kept;
  DragTally tally;
  std::vector<fs::path> files{fs::path(test::data) / "helix-126.json", fs::path(test::data) / "self-intersecting.json",
                              fs::path(test::data) / "partly-buildable.json"};
  for (const auto& entry : fs::directory_iterator(test::presets)) {
    if (entry.path().extension() == ".json" && entry.path().filename() != "preset.schema.json") files.push_back(entry.path());
  }
  for (const fs::path& file : files) {
    CAPTURE(file.string());
    const json preset = preset_object(preset_file(file));
    for (int k = 0; k < 3; ++k) drag(preset, rng, 8, kept, tally);
  }
  CAPTURE(tally.steps, tally.collisions, tally.kept);
  CHECK(tally.collisions > 0);
  CHECK(tally.steps - tally.collisions > 50);
  CHECK(tally.kept > 20);
}

TEST_CASE("the kept collision check at t*: a small drag step tests few pairs again", "[self-intersection][keep]") {
  // helix-126: 1,000 panels; apex height 3 moved by 1e-4 of the model a step.
  json preset = preset_file(fs::path(test::data) / "helix-126.json");
  TStarCollisions kept;
  const Design start = design_from_json(preset);
  REQUIRE(!kept.check(start));
  CHECK(kept.last().rebuilt);
  CHECK(kept.last().pairs > 1000);
  const double step = 1e-4 * start.assembly.model_size();
  for (int k = 1; k <= 5; ++k) {
    preset["apex_heights"][3] = preset["apex_heights"][3].get<double>() + step;
    const Design d = design_from_json(preset);
    REQUIRE(!kept.check(d));
    CHECK(!self_intersection_at_t_star(d));
    CHECK(!kept.last().rebuilt);
    CHECK(kept.last().tested < kept.last().pairs / 2);  // (the pairs that share a corner are always tested)
  }
  // A design of another mesh: made again.
  const Design other = load_design(fs::path(test::presets) / "grid-3x3.json");
  CHECK(!kept.check(other));
  CHECK(kept.last().rebuilt);
}
