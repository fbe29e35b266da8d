// A keep-buildable drag (issue 14): a height dragged through the place where a
// whole column of panels would cross; every step keeps the held height where
// the pointer put it and projects the other heights onto a design whose panels
// are simple and whose t* is free of collisions, continuing the last step's
// projection so that a step costs a few designs, not an optimizer run (the
// 60 Hz budget is measured by bench/designer.mjs, not here: evaluations are
// counted instead).

#include "phedra/design.h"
#include "phedra/errors.h"
#include "phedra/panel_nets.h"
#include "phedra/keep_buildable.h"
#include "phedra/repair.h"
#include "phedra/self_intersection.h"
#include "phedra/design_preset.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

using namespace phedra;
using json = nlohmann::json;

namespace {

json load(const std::string& name) {
  std::ifstream in(std::string(PHEDRA_TEST_DATA_DIR) + "/" + name);
  return json::parse(in);
}

/// Simple panels (the shape rule, MATH.md section 9) and no collision at t*, checked here.
bool simple_and_free(const json& preset) {
  const Design d = design_from_json(preset);
  return invalid_panels(d).empty() && !self_intersection_at_t_star(d);
}

}  // namespace

TEST_CASE("keep-buildable drag: a height dragged past its neighbour, 1000 panels, every step projected cheaply",
          "[repair][keep]") {
  json design = load("helix-126.json");  // apex_heights -1.5 1 -0.5 2.2 ...: height 1 dragged down past height 2
  REQUIRE(simple_and_free(design));
  KeepBuildableDrag drag;
  ProjectionOptions options;
  options.max_seconds = 1e9;  // counted, not timed
  const double start = design["apex_heights"][1].get<double>();
  std::size_t projected = 0, cheap = 0, worst = 0;
  for (int k = 1; k <= 60; ++k) {
    const double wanted = start - 0.03 * k;  // crosses -0.5 (height 2) near step 50
    CAPTURE(k, wanted);
    const json previous = design["apex_heights"][1];
    json moved = design;
    moved["apex_heights"][1] = wanted;
    std::optional<Projection> p;
    try {
      p = drag.step(moved, "/apex_heights/1", previous, options);
    } catch (const InvalidInputError&) {
      continue;  // (a height equal to its neighbour's does not build: the page keeps the last design)
    }
    REQUIRE(p);
    CHECK(p->preset["apex_heights"][1].get<double>() == wanted);
    CHECK(simple_and_free(p->preset));
    // Only apex heights change, and by no more than the drag has moved the held one.
    for (const std::string key : {"trajectory", "directions", "signs"}) CHECK(p->preset[key] == design[key]);
    for (std::size_t j = 0; j < design["apex_heights"].size(); ++j) {
      if (j == 1) continue;
      CHECK(std::abs(p->preset["apex_heights"][j].get<double>() - load("helix-126.json")["apex_heights"][j].get<double>()) <=
            std::abs(wanted - start) + 1e-12);
    }
    if (p->moved) {
      ++projected;
      if (p->how == "continued" || p->how == "neighbours") ++cheap;
      worst = std::max(worst, p->evaluations);
    }
    design = p->preset;
  }
  // Past the wall every step needed the projection, each found by a few designs.
  CHECK(projected >= 8);
  CHECK(cheap == projected);
  CHECK(worst <= 16);
  // The last step's continuation: a handful of designs.
  INFO("worst evaluations " << worst);
}

TEST_CASE("keep-buildable drag: a step that needs no projection costs one design", "[repair][keep]") {
  const json design = load("helix-126.json");
  KeepBuildableDrag drag;
  json moved = design;
  moved["apex_heights"][3] = 2.3;
  const std::optional<Projection> p = drag.step(moved, "/apex_heights/3", design["apex_heights"][3]);
  REQUIRE(p);
  CHECK(p->how == "already");
  CHECK(!p->moved);
  CHECK(p->evaluations == 1);
}

TEST_CASE("keep-buildable drag of a trajectory point: its neighbours follow it (a soft selection), 1000 panels",
          "[repair][keep]") {
  // On the dense helix a point moved by about one segment reverses a segment:
  // no apex height can undo that, the neighbouring points following can.
  const json original = load("helix-126.json");
  json design = original;
  KeepBuildableDrag drag;
  ProjectionOptions options;
  options.max_seconds = 1e9;  // counted, not timed
  const std::size_t held = 60;
  std::size_t projected = 0, worst = 0;
  for (int k = 1; k <= 25; ++k) {
    CAPTURE(k);
    const json previous = design["trajectory"][held];
    json moved = design;
    json wanted = original["trajectory"][held];
    wanted[0] = wanted[0].get<double>() + 0.02 * k;
    wanted[1] = wanted[1].get<double>() + 0.02 * k;
    moved["trajectory"][held] = wanted;
    const std::optional<Projection> p = drag.step(moved, "/trajectory/60", previous, options);
    REQUIRE(p);
    CHECK(p->preset["trajectory"][held] == wanted);
    CHECK(simple_and_free(p->preset));
    CHECK(p->preset["apex_heights"] == original["apex_heights"]);
    // Not much larger than the held point's own move makes the design (a quarter at most).
    json own = original;
    own["trajectory"][held] = wanted;
    CHECK(design_from_json(p->preset).assembly.model_size() <=
          1.25 * std::max(design_from_json(original).assembly.model_size(), design_from_json(own).assembly.model_size()));
    CHECK(p->preset["directions"] == original["directions"]);
    // Only points within the largest window (32 a side) move, each by at most the held point's move.
    for (std::size_t i = 0; i < original["trajectory"].size(); ++i) {
      const bool near = (i > held ? i - held : held - i) <= 32;
      for (int c = 0; c < 3; ++c) {
        const double d = std::abs(p->preset["trajectory"][i][c].get<double>() - original["trajectory"][i][c].get<double>());
        CHECK(d <= (near ? 0.02 * k + 1e-12 : 0.0));
      }
    }
    if (p->moved) {
      ++projected;
      CHECK(p->how == "trajectory");
      worst = std::max(worst, p->evaluations);
    }
    design = p->preset;
  }
  CHECK(projected >= 15);
  CHECK(worst <= 16);
}

TEST_CASE("keep-buildable drag: fields the caller holds too (the one that defines t*) stay, the held one's neighbours move",
          "[repair][keep]") {
  json design = load("helix-126.json");  // apex_heights -1.5 1 -0.5 2.2 ...
  const json original = design;
  KeepBuildableDrag drag;
  ProjectionOptions options;
  options.max_seconds = 1e9;
  options.fixed = {"/apex_heights/1"};  // held as the page holds the field of t*
  const double start = design["apex_heights"][3].get<double>();
  std::size_t projected = 0;
  for (int k = 1; k <= 50; ++k) {
    const double wanted = start - 0.05 * k;  // height 3 down past 0.4 (height 4): S_3 between S_2 and S_4
    CAPTURE(k, wanted);
    const json previous = design["apex_heights"][3];
    json moved = design;
    moved["apex_heights"][3] = wanted;
    std::optional<Projection> p;
    try {
      p = drag.step(moved, "/apex_heights/3", previous, options);
    } catch (const InvalidInputError&) {
      continue;
    }
    REQUIRE(p);
    CHECK(p->preset["apex_heights"][3].get<double>() == wanted);
    CHECK(p->preset["apex_heights"][1] == original["apex_heights"][1]);
    CHECK(simple_and_free(p->preset));
    if (p->moved) ++projected;
    design = p->preset;
  }
  CHECK(projected >= 3);
}
