// phedra repair as a user runs it (issue 14): one test per message, the
// repaired preset checked by `phedra check`, nothing written on failure.

#include "support/test_files.h"
#include "support/cli_run.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <unistd.h>

using phedra::test::data;
using phedra::test::presets;
using phedra::test::read_json;

using phedra::test::phedra_cli;
using phedra::test::Run;
using phedra::test::TempDir;
using Catch::Matchers::Contains;
using json = nlohmann::json;
namespace fs = std::filesystem;

namespace {

/// A parallelogram tube with monotone heights: four bow-ties, repaired in well under a second.
const std::string repairable = data + "/repairable-tube.json";

}  // namespace

TEST_CASE("repair: the nearest buildable design, written as a preset that phedra check passes", "[repair][cli]") {
  TempDir dir("repair");
  const std::string out = dir / "repaired.json";
  const Run r = phedra_cli({"repair", repairable, "-o", out});
  INFO(r.out << r.err);
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Contains("before: not buildable: 4 of 20 panels cannot be cut as one plate"));
  CHECK_THAT(r.out, Contains("after:  buildable over the whole flexion interval"));
  CHECK_THAT(r.out, Contains("tube.apex_heights["));
  CHECK_THAT(r.out, Contains("of the model size)"));
  CHECK_THAT(r.out, Contains("wrote " + out));
  CHECK_THAT(r.out, Contains("designs built"));
  const json repaired = read_json(out);
  const json input = read_json(repairable);
  CHECK(repaired["name"] == "repairable-tube-repaired");
  CHECK_THAT(repaired["description"].get<std::string>(), Contains("Repaired by phedra repair"));
  CHECK(repaired["trajectory"] == input["trajectory"]);  // not varied by default
  CHECK(repaired["tube"]["type"] == "parallelogram");
  CHECK(repaired["tube"]["apex_heights"] != input["tube"]["apex_heights"]);
  // The keys keep the input's order (a preset stays readable).
  std::ifstream text(out);
  std::string first, second;
  std::getline(text, first);
  std::getline(text, second);
  CHECK_THAT(second, Contains("\"$schema\""));
  const Run check = phedra_cli({"check", out, "--samples", "20"});
  INFO(check.out);
  CHECK(check.code == 0);
  CHECK_THAT(check.out, Contains("PASS"));
}

TEST_CASE("repair --json: the changes, both reports, the search's figures", "[repair][cli]") {
  TempDir dir("repair");
  const Run r = phedra_cli({"repair", repairable, "-o", dir / "r.json", "--json"});
  REQUIRE(r.code == 0);
  const json j = json::parse(r.out);
  CHECK(j["found"] == true);
  CHECK(j["already_buildable"] == false);
  CHECK(j["fraction"] == 1.0);
  CHECK(j["before"]["buildable"] == false);
  CHECK(j["after"]["buildable"] == true);
  REQUIRE(j["changes"].size() >= 1);
  const double size = std::abs(j["changes"][0]["change"].get<double>()) / j["changes"][0]["relative"].get<double>();
  CHECK(size > 1.0);  // the input's model size, the same for every field
  for (const json& c : j["changes"]) {
    CHECK(c["field"].get<std::string>().rfind("tube.apex_heights[", 0) == 0);
    CHECK(c["relative"].get<double>() == Approx(std::abs(c["change"].get<double>()) / size).epsilon(1e-9));
  }
  CHECK(j["distance"].get<double>() > 0.0);
  CHECK(j["evaluations"].get<int>() > 0);
  CHECK(j["seconds"].get<double>() > 0.0);
  CHECK(j["closest"].is_null());
}

TEST_CASE("repair: an already buildable design is left alone, nothing written", "[repair][cli]") {
  TempDir dir("repair");
  const Run r = phedra_cli({"repair", presets + "/default.json", "-o", dir / "r.json"});
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Contains("already buildable as required: nothing to repair, nothing written"));
  CHECK_FALSE(fs::exists(dir / "r.json"));
}

TEST_CASE("repair: an anti-parallelogram tube cannot be repaired, by its kind (exit 1, nothing written)", "[repair][cli]") {
  TempDir dir("repair");
  const Run r = phedra_cli({"repair", presets + "/anti-parallelogram-tube.json", "-o", dir / "r.json"});
  CHECK(r.code == 1);
  CHECK_THAT(r.out, Contains("no buildable design found: its anti-parallelogram tube crosses itself by kind"));
  CHECK_THAT(r.out, Contains("nothing written"));
  CHECK_FALSE(fs::exists(dir / "r.json"));
}

TEST_CASE("repair: out of time, exit 1, how close it came, the closest design on request", "[repair][cli]") {
  TempDir dir("repair");
  const Run r = phedra_cli({"repair", repairable, "-o", dir / "r.json", "--max-seconds", "1e-6", "--closest",
                            dir / "closest.json"});
  INFO(r.out);
  CHECK(r.code == 1);
  CHECK_THAT(r.out, Contains("no buildable design found: "));
  CHECK_THAT(r.out, Contains("stay not simple"));
  CHECK_FALSE(fs::exists(dir / "r.json"));
  REQUIRE(fs::exists(dir / "closest.json"));
  CHECK(read_json(dir / "closest.json")["name"] == "repairable-tube-closest");
}

TEST_CASE("repair --require: a part of the interval around t*", "[repair][cli]") {
  TempDir dir("repair");
  const Run r = phedra_cli({"repair", repairable, "-o", dir / "r.json", "--require", "0.5", "--json"});
  REQUIRE(r.code == 0);
  CHECK(json::parse(r.out)["fraction"].get<double>() >= 0.5);
}

TEST_CASE("repair: bad options and presets exit 2 naming the option or field", "[repair][cli]") {
  TempDir dir("repair");
  const std::string out = dir / "r.json";
  auto fails = [&](const std::vector<std::string>& args, const std::string& message) {
    const Run r = phedra_cli(args);
    INFO(r.err);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Contains(message));
    CHECK_FALSE(fs::exists(out));
  };
  fails({"repair", repairable, "-o", out, "--vary", "heights"}, "--vary: unknown group \"heights\"");
  fails({"repair", repairable, "-o", out, "--vary", ""}, "--vary");
  fails({"repair", repairable, "-o", dir / "r.txt"}, "--output: the repaired preset is written as .json");
  fails({"repair", repairable, "-o", out, "--closest", dir / "c.txt"}, "--closest: the closest design is written as .json");
  fails({"repair", repairable, "-o", out, "--require", "1.5"}, "--require");
  fails({"repair", repairable, "-o", out, "--objective", "fewest"}, "--objective");
  fails({"repair", repairable, "-o", out, "--max-growth", "-2"}, "--max-growth");
  fails({"repair", presets + "/helix-tube.json", "-o", out, "--vary", "directions"},
        "--vary: nothing to change: the preset has no numbers in the groups asked for");
  fails({"repair", data + "/bad/apexes-consecutive-equal.json", "-o", out}, "apex_heights[2]: equals apex_heights[1]");
}

TEST_CASE("repair --objective fields: says how many fields the nearest design changes", "[repair][cli]") {
  TempDir dir("repair");
  const Run r = phedra_cli({"repair", repairable, "-o", dir / "r.json", "--objective", "fields"});
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Contains("changed 1 field (the nearest design changes 1)"));
  const Run j = phedra_cli({"repair", repairable, "-o", dir / "j.json", "--objective", "fields", "--json"});
  CHECK(nlohmann::json::parse(j.out)["nearest_changes"] == 1);
  CHECK(phedra_cli({"check", dir / "r.json"}).code == 0);
}

TEST_CASE("repair: an output that cannot be written exits 3", "[repair][cli]") {
  const Run r = phedra_cli({"repair", repairable, "-o", "/nonexistent-dir/r.json"});
  CHECK(r.code == 3);
}
