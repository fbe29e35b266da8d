// Presets: round trip, reference case files, the schema in presets/ agrees
// with the parser.

#include "phedra/errors.h"
#include "phedra/phedron.h"
#include "phedra/preset.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <set>

using namespace phedra;
using nlohmann::json;

TEST_CASE("a preset round-trips through JSON", "[preset]") {
  const ControlPolylines in = load_preset(std::string(PHEDRA_PRESETS_DIR) + "/tilted-axis.json");
  const ControlPolylines again = preset_from_json(preset_to_json(in));
  CHECK(again.name == in.name);
  CHECK(again.trajectory == in.trajectory);
  CHECK(again.directions == in.directions);
  CHECK(again.axis == in.axis);
  CHECK(again.apex_heights == in.apex_heights);
  CHECK(again.signs == in.signs);
  CHECK(signs_to_string(again.signs) == "+-+-+");
}

TEST_CASE("a reference case file loads as its preset", "[preset]") {
  const std::string file = std::string(PHEDRA_TEST_DATA_DIR) + "/cases/open-all-minus.json";
  const ControlPolylines from_file = load_preset(file);
  const json c = json::parse(std::ifstream(file));
  const ControlPolylines from_object = preset_from_json(c["preset"]);
  CHECK(from_file.trajectory == from_object.trajectory);
  CHECK(from_file.name == "open-all-minus");
}

TEST_CASE("the axis defaults to z", "[preset]") {
  const ControlPolylines in = parse_preset(
      R"({"trajectory": [[2,0,0],[1.2,1.5,0.4]], "directions": [[1,0,0],[1.2,1.5,0]], "apex_heights": [-1,0.5,-0.3], "signs": "+"})");
  CHECK(in.axis == Vec3::UnitZ());
  CHECK(in.name == "unnamed");
  CHECK_NOTHROW(PHedron(in));
}

TEST_CASE("the JSON schema lists exactly the keys the parser knows", "[preset]") {
  const json schema = json::parse(std::ifstream(std::string(PHEDRA_PRESETS_DIR) + "/preset.schema.json"));
  std::set<std::string> properties;
  for (const auto& [key, value] : schema["properties"].items()) properties.insert(key);
  CHECK(properties == std::set<std::string>{"$schema", "name", "description", "trajectory", "directions", "axis",
                                            "apex_heights", "signs", "tube", "grid", "row", "couplings", "merge"});
  std::set<std::string> required(schema["required"].begin(), schema["required"].end());
  CHECK(required == std::set<std::string>{"trajectory", "directions"});
  // Every key the schema allows is accepted, and one it does not is refused.
  json preset = json::parse(std::ifstream(std::string(PHEDRA_PRESETS_DIR) + "/default.json"));
  CHECK_NOTHROW(preset_from_json(preset));
  preset["colour"] = "red";
  CHECK_THROWS_AS(preset_from_json(preset), InvalidInputError);
}
