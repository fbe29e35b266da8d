// One test per violated assumption: the error names the field (and index) and
// says which assumption.

#include "phedra/errors.h"
#include "phedra/phedron.h"
#include "phedra/preset.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

using namespace phedra;
using Catch::Matchers::Contains;

namespace {

/// A valid input whose apex line pi_0 ∩ pi_1 is the z-axis (case (b), t* = 0.5).
ControlPolylines base() {
  ControlPolylines in;
  in.name = "base";
  in.trajectory = {Vec3(2, 0, 0), Vec3(1.2, 1.5, 0.4), Vec3(0.1, 2.3, 0.9), Vec3(-1.1, 2.4, 1.3)};
  in.directions = {Vec3(1, 0, 0), Vec3(1.2, 1.5, 0), Vec3(-0.2, 1, 0), Vec3(-0.7, 0.7, 0)};
  in.apex_heights = {-1, 0.5, -0.3, 1.2, 0.1};
  in.signs = {Sign::plus, Sign::minus, Sign::plus};
  return in;
}

struct Failure {
  std::string field;
  std::string message;
};

Failure failure_of(const ControlPolylines& in) {
  try {
    PHedron p(in);
  } catch (const InvalidInputError& e) {
    return {e.field(), e.what()};
  }
  return {"<none>", "<constructed without error>"};
}

Failure failure_of_text(const std::string& text) {
  try {
    PHedron p(parse_preset(text));
  } catch (const InvalidInputError& e) {
    return {e.field(), e.what()};
  }
  return {"<none>", "<constructed without error>"};
}

}  // namespace

TEST_CASE("the base input is valid", "[errors]") { CHECK_NOTHROW(PHedron(base())); }

TEST_CASE("zero direction", "[errors]") {
  auto in = base();
  in.directions[2] = Vec3::Zero();
  const Failure f = failure_of(in);
  CHECK(f.field == "directions[2]");
  CHECK_THAT(f.message, Contains("zero vector"));
}

TEST_CASE("direction not orthogonal to the axis", "[errors]") {
  auto in = base();
  in.directions[1].z() = 0.3;
  const Failure f = failure_of(in);
  CHECK(f.field == "directions[1]");
  CHECK_THAT(f.message, Contains("not orthogonal to the axis"));
}

TEST_CASE("consecutive profile planes parallel", "[errors]") {
  auto in = base();
  in.directions[3] = in.directions[2] * 2.0;
  const Failure f = failure_of(in);
  CHECK(f.field == "directions[3]");
  CHECK_THAT(f.message, Contains("profile planes 2 and 3 are parallel"));
}

TEST_CASE("consecutive profile planes identical: a bifurcation configuration", "[errors]") {
  auto in = base();
  in.directions[3] = in.directions[2];
  in.trajectory[3] = in.trajectory[2] + 0.8 * in.directions[2] + Vec3(0, 0, 0.4);
  const Failure f = failure_of(in);
  CHECK(f.field == "directions[3]");
  CHECK_THAT(f.message, Contains("profile planes 2 and 3 are identical"));
  CHECK_THAT(f.message, Contains("bifurcation configuration"));
}

TEST_CASE("V_{0,0} on the apex line", "[errors]") {
  auto in = base();
  // A point of pi_1 is on pi_0 ∩ pi_1 once pi_0 passes through it.
  in.trajectory[0] = in.trajectory[1] - 0.5 * in.directions[1].normalized() * 3.0 + Vec3(0, 0, -0.7);
  in.directions[0] = Vec3(0.3, -1, 0);
  const Failure f = failure_of(in);
  CHECK(f.field == "trajectory[0]");
  CHECK_THAT(f.message, Contains("lies on the apex line"));
}

TEST_CASE("three consecutive apexes not pairwise distinct", "[errors]") {
  auto in = base();
  in.apex_heights[3] = in.apex_heights[1];
  const Failure f = failure_of(in);
  CHECK(f.field == "apex_heights[3]");
  CHECK_THAT(f.message, Contains("pairwise distinct"));
  in = base();
  in.apex_heights[2] = in.apex_heights[1];
  CHECK(failure_of(in).field == "apex_heights[2]");
}

TEST_CASE("sign string of the wrong length", "[errors]") {
  auto in = base();
  in.signs.pop_back();
  const Failure f = failure_of(in);
  CHECK(f.field == "signs");
  CHECK_THAT(f.message, Contains("expected 3 signs"));
}

TEST_CASE("sign string with a wrong character", "[errors]") {
  std::string text = preset_to_json(base()).dump();
  text.replace(text.find("\"+-+\""), 5, "\"+x+\"");
  const Failure f = failure_of_text(text);
  CHECK(f.field == "signs[1]");
  CHECK_THAT(f.message, Contains("expected '+' or '-', got 'x'"));
}

TEST_CASE("trajectory orthogonal to the axis: a T-hedron", "[errors]") {
  auto in = base();
  for (Vec3& p : in.trajectory) p.z() = 0.25;
  const Failure f = failure_of(in);
  CHECK(f.field == "trajectory");
  CHECK_THAT(f.message, Contains("T-hedron"));
}

TEST_CASE("scissor case with a '-' sign (paper, Remark 1)", "[errors]") {
  auto in = base();
  // |S_0 - V_{0,0}| = |S_1 - V_{0,0}|: heights symmetric about V_{0,0} (z = 0).
  in.apex_heights[1] = -in.apex_heights[0];
  const Failure f = failure_of(in);
  CHECK(f.field == "signs[1]");
  CHECK_THAT(f.message, Contains("scissor"));
  CHECK_THAT(f.message, Contains("Remark 1"));
  // The same heights with only '+' signs are a valid scissor-like P-hedron.
  in.signs = {Sign::plus, Sign::plus, Sign::plus};
  CHECK_NOTHROW(PHedron(in));
}

TEST_CASE("trajectory edge parallel to its profile plane", "[errors]") {
  auto in = base();
  const Vec3 edge = in.trajectory[2] - in.trajectory[1];
  in.directions[2] = Vec3(edge.x(), edge.y(), 0);
  const Failure f = failure_of(in);
  CHECK(f.field == "trajectory[2]");
  CHECK_THAT(f.message, Contains("parallel to profile plane 2"));
}

TEST_CASE("a sigma- image at (near) infinity", "[errors]") {
  auto in = base();
  in.signs = {Sign::minus, Sign::plus, Sign::plus};
  // Almost the scissor case: V_{0,0} lies 1e-10 off the vanishing line of sigma- at S_1.
  in.apex_heights[1] = -in.apex_heights[0] + 2e-10;
  const Failure f = failure_of(in);
  CHECK(f.field == "signs[0]");
  CHECK_THAT(f.message, Contains("to infinity"));
}

TEST_CASE("input in a bifurcation configuration (t* at a flexion limit)", "[errors]") {
  // The identical-planes case above is the exact bifurcation; planes 1e-8 rad apart
  // pass that test but leave strip 3 numerically at its flexion limit.
  auto in = base();
  const Vec3 d = in.directions[2].normalized();
  in.directions[3] = d + 1e-8 * Vec3(-d.y(), d.x(), 0);
  in.trajectory[3] = in.trajectory[2] + 0.8 * d + Vec3(0, 0, 0.4);
  const Failure f = failure_of(in);
  CHECK(f.field == "directions[3]");
  CHECK_THAT(f.message, Contains("bifurcation configuration"));
  CHECK_THAT(f.message, Contains("strip 3 is at its flexion limit"));
}

TEST_CASE("non-finite numbers", "[errors]") {
  auto in = base();
  in.trajectory[1].y() = std::numeric_limits<double>::quiet_NaN();
  CHECK(failure_of(in).field == "trajectory[1][1]");
  CHECK_THAT(failure_of(in).message, Contains("not a finite number"));
  in = base();
  in.apex_heights[4] = std::numeric_limits<double>::infinity();
  CHECK(failure_of(in).field == "apex_heights[4]");
  // In JSON, a number too large for a double.
  std::string text = preset_to_json(base()).dump();
  text.replace(text.find("-1.0,0.5"), 4, "-1e999");
  const Failure f = failure_of_text(text);
  CHECK_THAT(f.message, Contains("not a finite number at line 1"));
  CHECK_THAT(f.message, Contains("1e999"));
}

TEST_CASE("malformed JSON names line and column", "[errors]") {
  const Failure f = failure_of_text("{\n  \"trajectory\": [[1, 0, 0],\n    [2, 0 0]]\n}");
  CHECK(f.field.empty());
  CHECK_THAT(f.message, Contains("malformed JSON at line 3, column 11"));
  CHECK_THAT(failure_of_text("{\"trajectory\": ").message, Contains("malformed JSON at line 1"));
  CHECK_THAT(failure_of_text("").message, Contains("malformed JSON at line 1, column 1"));
}

TEST_CASE("fewer than 2 profiles or 3 apexes", "[errors]") {
  auto in = base();
  in.trajectory.resize(1);
  in.directions.resize(1);
  CHECK(failure_of(in).field == "trajectory");
  CHECK_THAT(failure_of(in).message, Contains("at least 2 points"));
  in = base();
  in.apex_heights = {0.1, 0.7};
  in.signs = {};
  CHECK(failure_of(in).field == "apex_heights");
  CHECK_THAT(failure_of(in).message, Contains("at least 3 apexes"));
}

TEST_CASE("t outside the flexion interval states the interval", "[errors]") {
  const PHedron p(base());
  const double beyond = p.flexion_interval().upper.t + 0.01;
  CHECK_THROWS_AS(p.evaluate(beyond), OutOfIntervalError);
  CHECK_THROWS_WITH(p.evaluate(beyond), Contains("outside the flexion interval [") &&
                                            Contains(std::to_string(p.flexion_interval().lower.t).substr(0, 6)));
  CHECK_THROWS_WITH(p.t_at_fraction(1.5), Contains("must be in [0, 1]"));
  CHECK_NOTHROW(p.evaluate(p.flexion_interval().lower.t));
  CHECK_NOTHROW(p.evaluate(p.flexion_interval().upper.t));
}

TEST_CASE("other input errors: counts, axis, duplicates, keys, types", "[errors]") {
  auto in = base();
  in.directions.pop_back();
  CHECK_THAT(failure_of(in).message, Contains("directions: expected 4 vectors"));

  in = base();
  in.axis = Vec3::Zero();
  CHECK(failure_of(in).field == "axis");
  CHECK_THAT(failure_of(in).message, Contains("zero vector"));
  in.axis = Vec3(0, 0, 2);
  CHECK_THAT(failure_of(in).message, Contains("must be a unit vector, its length is 2"));

  in = base();
  in.trajectory[2] = in.trajectory[1];
  CHECK(failure_of(in).field == "trajectory[2]");
  CHECK_THAT(failure_of(in).message, Contains("coincides with trajectory[1]"));

  const std::string good = preset_to_json(base()).dump();
  auto without = [&](const std::string& key) {
    auto j = nlohmann::json::parse(good);
    j.erase(key);
    return j.dump();
  };
  CHECK(failure_of_text(without("trajectory")).field == "trajectory");
  CHECK_THAT(failure_of_text(without("apex_heights")).message, Contains("missing"));
  auto j = nlohmann::json::parse(good);
  j["trajectroy"] = 1;
  CHECK(failure_of_text(j.dump()).field == "trajectroy");
  CHECK_THAT(failure_of_text(j.dump()).message, Contains("unknown key"));
  j = nlohmann::json::parse(good);
  j["trajectory"][2] = {1, 2};
  CHECK(failure_of_text(j.dump()).field == "trajectory[2]");
  CHECK_THAT(failure_of_text(j.dump()).message, Contains("expected an array of 3 numbers"));
  j = nlohmann::json::parse(good);
  j["apex_heights"][1] = "0.5";
  CHECK(failure_of_text(j.dump()).field == "apex_heights[1]");
  CHECK_THAT(failure_of_text(j.dump()).message, Contains("expected a number, got string"));
  j = nlohmann::json::parse(good);
  j["signs"] = {"+", "-", "+"};
  CHECK_THAT(failure_of_text(j.dump()).message, Contains("expected a string of '+' and '-'"));
  CHECK_THAT(failure_of_text("[1, 2]").message, Contains("must be a JSON object"));
}
