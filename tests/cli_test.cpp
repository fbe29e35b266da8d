// The `phedra` command, run in-process: outputs, exit codes and files.

#include "support/test_files.h"
#include "support/cli_run.h"
#include "cli.h"
#include "phedra/phedron.h"
#include "phedra/preset.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

using phedra::test::data;
using phedra::test::presets;

using namespace phedra;
using Catch::Matchers::Contains;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

struct Run {
  int code;
  std::string out;
  std::string err;
};

Run phedra_cli(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  const int code = cli::run(args, out, err);
  return {code, out.str(), err.str()};
}


fs::path scratch_directory() {
  const fs::path dir = fs::temp_directory_path() / ("phedra-cli-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

std::vector<fs::path> files_in(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir)) files.push_back(entry.path());
  return files;
}

}  // namespace

TEST_CASE("info prints the figures, --json has the documented keys", "[cli]") {
  const std::string preset = data + "/cases/open-all-plus.json";
  const Run text = phedra_cli({"info", preset});
  CHECK(text.code == 0);
  CHECK_THAT(text.out, Contains("t*:                -1.29797\n"));  // 6 significant digits for people
  CHECK_THAT(text.out, Contains("flexion interval:"));
  // --full-precision: round-trip digits, as in the files.
  const Run full = phedra_cli({"info", preset, "--full-precision"});
  CHECK_THAT(full.out, Contains("t*:                -1.2979729609766277\n"));
  const Run j = phedra_cli({"info", preset, "--json"});
  REQUIRE(j.code == 0);
  const json info = json::parse(j.out);
  CHECK(info["t_star"].get<double>() == -1.2979729609766277);
  CHECK(info["case"] == "a");
  CHECK(info["flexion_interval"].size() == 2);
  CHECK(info["vertices"] == 30);
  CHECK(info["faces"] == 20);
  CHECK(info["planarity"].get<double>() < 1e-9);
  CHECK(info["isometry"].get<double>() < 1e-9);
}

TEST_CASE("text output has 6 significant digits in every command, --full-precision gives round-trip digits", "[cli]") {
  // No number in a command's text output has more than 6 significant digits.
  const fs::path dir = scratch_directory();
  const std::string tube = presets + "/parallelogram-tube.json";
  const std::vector<std::vector<std::string>> commands{
      {"info", tube},
      {"check", tube},
      {"intersections", tube},
      {"metrics", tube, "--samples", "5"},
      {"generate", tube, "-o", (dir / "p.glb").string()},
      {"outlines", tube, "-o", (dir / "p.pdf").string()},
      {"repair", data + "/repairable-tube.json", "-o", (dir / "r.json").string()},
      {"develop", presets + "/developed/flat-pattern.json"},
  };
  // The most significant digits of any decimal number in a text (leading zeros and exponents aside).
  auto most_digits = [](const std::string& text) {
    std::size_t most = 0;
    const std::regex number("[0-9]+\\.[0-9]+");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), number); it != std::sregex_iterator(); ++it) {
      std::string digits;
      for (char c : it->str()) {
        if (c != '.') digits += c;
      }
      digits.erase(0, std::min(digits.find_first_not_of('0'), digits.size()));
      most = std::max(most, digits.size());
    }
    return most;
  };
  for (const auto& args : commands) {
    CAPTURE(args);
    const Run r = phedra_cli(args);
    CHECK(r.code == 0);
    CHECK(most_digits(r.out + r.err) <= 6);
    auto with_full = args;
    with_full.push_back("--full-precision");
    const Run f = phedra_cli(with_full);
    CHECK(f.code == 0);
    if (args[0] != "outlines") CHECK(most_digits(f.out) > 6);
  }
  fs::remove_all(dir);
}

TEST_CASE("sample: labels, faces, samples in command-line order, fractions 0 and 1 are the limits", "[cli]") {
  const std::string preset = presets + "/default.json";
  const PHedron p(load_preset(preset));
  const Run r = phedra_cli({"sample", preset, "--fraction", "1", "--t", "1.0", "--fraction", "0"});
  REQUIRE(r.code == 0);
  const json s = json::parse(r.out);
  REQUIRE(s["samples"].size() == 3);
  CHECK(s["samples"][0]["t"].get<double>() == p.flexion_interval().upper.t);
  CHECK(s["samples"][1]["t"].get<double>() == 1.0);
  CHECK(s["samples"][2]["t"].get<double>() == p.flexion_interval().lower.t);
  CHECK(s["labels"].size() == p.vertex_count());
  CHECK(s["labels"][0] == json::array({0, 0}));
  CHECK(s["labels"][p.topology().columns() + 1] == json::array({1, 1}));
  CHECK(s["faces"].size() == p.topology().faces().size());
  const Points v = p.evaluate(1.0);
  for (std::size_t k = 0; k < v.size(); ++k) {
    for (int c = 0; c < 3; ++c) CHECK(s["samples"][1]["vertices"][k][c].get<double>() == v[k][c]);
  }
  const Run count = phedra_cli({"sample", preset, "--count", "5"});
  CHECK(json::parse(count.out)["samples"].size() == 5);
}

TEST_CASE("sample -o writes the file atomically and never over the input", "[cli]") {
  const fs::path dir = scratch_directory();
  const std::string preset = presets + "/default.json";
  const fs::path out = dir / "samples.json";
  CHECK(phedra_cli({"sample", preset, "--count", "3", "-o", out.string()}).code == 0);
  CHECK(json::parse(std::ifstream(out))["samples"].size() == 3);

  // A missing directory: exit 3, nothing written.
  const Run missing = phedra_cli({"sample", preset, "--t", "1", "-o", (dir / "no" / "such" / "x.json").string()});
  CHECK(missing.code == 3);
  CHECK_THAT(missing.err, Contains("does not exist"));

  // The input itself: refused, unchanged.
  const fs::path copy = dir / "preset.json";
  fs::copy_file(preset, copy, fs::copy_options::overwrite_existing);
  const auto before = fs::file_size(copy);
  const Run over = phedra_cli({"sample", copy.string(), "--t", "1", "-o", copy.string()});
  CHECK(over.code == 3);
  CHECK_THAT(over.err, Contains("is the input file"));
  CHECK(fs::file_size(copy) == before);

  // A t outside the interval: exit 2, no file, no temporary left behind.
  const fs::path bad = dir / "bad.json";
  const Run outside = phedra_cli({"sample", preset, "--t", "100", "-o", bad.string()});
  CHECK(outside.code == 2);
  CHECK_THAT(outside.err, Contains("outside the flexion interval"));
  CHECK_FALSE(fs::exists(bad));
  for (const fs::path& f : files_in(dir)) CHECK(f.extension() != ".tmp");
  fs::remove_all(dir);
}

TEST_CASE("check passes on the shipped presets and the open reference cases", "[cli]") {
  // Every shipped preset is buildable over its whole flexion interval, except the
  // anti-parallelogram family: self-crossing by its kind (MATH.md section 6).
  for (const auto& entry : fs::directory_iterator(presets)) {
    if (entry.path().extension() != ".json" || entry.path().filename().string().find("schema") != std::string::npos)
      continue;
    CAPTURE(entry.path());
    const Run r = phedra_cli({"check", entry.path().string(), "--samples", "100"});
    CHECK_THAT(r.out, Contains("geometry PASS"));
    if (entry.path().filename().string().rfind("anti-parallelogram", 0) == 0) {
      CHECK(r.code == 1);
      CHECK_THAT(r.out, Contains("FAIL: ") && Contains("not buildable, by its kind"));
      CHECK(phedra_cli({"check", entry.path().string(), "--samples", "100", "--geometry-only"}).code == 0);
    } else {
      CHECK(r.code == 0);
      CHECK_THAT(r.out, Contains("PASS: ") && Contains("buildable over the whole flexion interval"));
    }
  }
  // Reference cases are random designs: their geometry is checked (they have bow-ties).
  const Run j = phedra_cli({"check", data + "/cases/open-mixed-tilted-axis.json", "--json", "--geometry-only"});
  CHECK(j.code == 0);
  const json report = json::parse(j.out);
  CHECK(report["passed"] == true);
  CHECK(report["samples"] == 201);
  CHECK(report["planarity"]["relative"].get<double>() < 1e-9);
}

TEST_CASE("check exits 1 when a figure exceeds the tolerance", "[cli]") {
  const Run r = phedra_cli({"check", presets + "/default.json", "--tolerance", "1e-30"});
  CHECK(r.code == 1);
  CHECK_THAT(r.out, Contains("FAIL"));
}

TEST_CASE("bad input and bad usage: clear message, exit 2, unreadable file: exit 3", "[cli]") {
  const fs::path dir = scratch_directory();
  const fs::path bad = dir / "bad.json";
  std::ofstream(bad) << "{\"trajectory\": [[1,0,0],[2,0,0]],\n \"directions\": [[1,0,0],[0,1,0]], \"apex_heights\": "
                        "[1,2,3], \"signs\": \"+-\"}";
  const Run r = phedra_cli({"info", bad.string()});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains(bad.string() + ": signs: expected 1 signs"));
  CHECK(phedra_cli({"info", (dir / "missing.json").string()}).code == 3);
  CHECK(phedra_cli({"info"}).code == 2);
  // A usage error points at the command's own help.
  const Run usage = phedra_cli({"sample", presets + "/default.json", "--frobnicate"});
  CHECK(usage.code == 2);
  CHECK_THAT(usage.err, Contains("Run `phedra sample --help` for usage."));
  CHECK_THAT(phedra_cli({"frobnicate"}).err, Contains("Run `phedra --help` for usage."));
  CHECK(phedra_cli({"frobnicate"}).code == 2);
  CHECK(phedra_cli({"sample", presets + "/default.json"}).code == 2);
  CHECK(phedra_cli({"sample", presets + "/default.json", "--fraction", "2"}).code == 2);
  CHECK(phedra_cli({"check", presets + "/default.json", "--samples", "1"}).code == 2);
  // --ease is a fraction of the animation at each end: at most a half.
  const Run ease = phedra_cli({"generate", presets + "/default.json", "-o", (dir / "e.glb").string(), "--ease", "0.7"});
  CHECK(ease.code == 2);
  CHECK_THAT(ease.err, Contains("--ease"));
  CHECK(!fs::exists(dir / "e.glb"));
  fs::remove_all(dir);
}

TEST_CASE("a file that is not a preset is named for what it is, in every command and in view", "[cli]") {
  const fs::path dir = scratch_directory();
  const std::string pattern = presets + "/developed/flat-pattern.json";
  const Run developed = phedra_cli({"info", pattern});
  CHECK(developed.code == 2);
  CHECK_THAT(developed.err, Contains("developed: this is a developed (flat) pattern, not a preset: `phedra develop FILE`"));
  REQUIRE(phedra_cli({"generate", presets + "/default.json", "-o", (dir / "m.glb").string(), "-q"}).code == 0);
  REQUIRE(phedra_cli({"generate", presets + "/default.json", "-o", (dir / "m.gltf").string(), "-q"}).code == 0);
  REQUIRE(phedra_cli({"generate", presets + "/default.json", "-o", (dir / "m.json").string(), "--count", "2"}).code == 0);
  const Run glb = phedra_cli({"info", (dir / "m.glb").string()});
  CHECK(glb.code == 2);
  CHECK_THAT(glb.err, Contains("this is a binary glTF file (.glb), not a JSON preset: `phedra view FILE.glb` shows it"));
  const Run gltf = phedra_cli({"check", (dir / "m.gltf").string()});
  CHECK(gltf.code == 2);
  CHECK_THAT(gltf.err, Contains("this is a glTF file, not a preset"));
  const Run motion = phedra_cli({"sample", (dir / "m.json").string(), "--count", "2"});
  CHECK(motion.code == 2);
  CHECK_THAT(motion.err, Contains("this is a motion JSON (written by `phedra sample` or `generate -o X.json`), not a preset"));
  // FOLD written under a .json name (generate picks the format from .fold only): write one by hand.
  std::ofstream(dir / "f.json") << R"({"file_spec": 1.2, "vertices_coords": [[0, 0, 0]]})";
  const Run fold = phedra_cli({"info", (dir / "f.json").string()});
  CHECK(fold.code == 2);
  CHECK_THAT(fold.err, Contains("this is a FOLD file, not a preset"));
  // view validates a preset before serving: the same error, exit 2, no server.
  const Run view = phedra_cli({"view", (dir / "m.json").string(), "--port", "0", "--requests", "1"});
  CHECK(view.code == 2);
  CHECK_THAT(view.err, Contains("this is a motion JSON"));
  CHECK(view.out.find("designer for") == std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("--help of every command exits 0 and describes it", "[cli]") {
  CHECK_THAT(phedra_cli({"--help"}).out, Contains("Exit codes"));
  CHECK_THAT(phedra_cli({"info", "--help"}).out, Contains("--json"));
  CHECK_THAT(phedra_cli({"sample", "--help"}).out, Contains("--fraction"));
  CHECK_THAT(phedra_cli({"check", "--help"}).out, Contains("--samples"));
  CHECK(phedra_cli({"check", "--help"}).code == 0);
  CHECK_THAT(phedra_cli({"--version"}).out, Contains("phedra 0."));
}

TEST_CASE("generate writes the mesh and the motion of tubes and arrays", "[cli]") {
  const fs::path dir = scratch_directory();
  const fs::path out = dir / "grid.json";
  const Run r = phedra_cli({"generate", presets + "/grid-3x3.json", "-o", out.string()});
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Contains("3 x 3 grid of parallelogram cells"));
  const json g = json::parse(std::ifstream(out));
  CHECK(g["members"].size() == 9);
  CHECK(g["samples"].size() == 41);
  CHECK(g["labels"][0].size() == 3);
  CHECK(g["face_members"].size() == g["faces"].size());
  CHECK(g["samples"][0]["vertices"].size() == g["labels"].size());

  const fs::path merged = dir / "merged.json";
  CHECK(phedra_cli({"generate", presets + "/merged-tube.json", "-o", merged.string(), "--count", "3"}).code == 0);
  const json m = json::parse(std::ifstream(merged));
  CHECK(m["kind"] == "merged assembly of 3 tubes");
  CHECK(m["faces"].size() == 80);  // an octagonal tube over 10 strips
  CHECK(m["labels"].size() == 88);

  const fs::path tube = dir / "tube.json";
  CHECK(phedra_cli({"generate", presets + "/parallelogram-tube.json", "-o", tube.string(), "--t", "1"}).code == 0);
  const json t = json::parse(std::ifstream(tube));
  CHECK(t["labels"][0].size() == 2);  // a single P-hedron keeps [i, c]
  CHECK(t["faces"].size() == 40);
  CHECK(phedra_cli({"generate", presets + "/grid-3x3.json"}).code == 2);  // -o is required
  fs::remove_all(dir);
}

TEST_CASE("check on tubes and arrays: the asymmetric anti-parallelogram fails with its gap", "[cli]") {
  const Run r = phedra_cli({"check", data + "/cases/tube-antiparallelogram-asymmetric.json", "--json"});
  CHECK(r.code == 1);
  const json report = json::parse(r.out);
  CHECK(report["closure"]["value"].get<double>() == Approx(1.144259069340053).epsilon(1e-6));
  CHECK_THAT(report["warning"].get<std::string>(), Contains("z_0 + z_2 = z_1 + z_3"));
  const Run info = phedra_cli({"info", data + "/cases/tube-antiparallelogram-asymmetric.json"});
  CHECK(info.code == 0);
  CHECK_THAT(info.out, Contains("warning:") && Contains("closed at t* only"));
  for (const std::string name : {"tube-parallelogram", "tube-antiparallelogram"}) {
    const Run ok = phedra_cli({"check", data + "/cases/" + name + ".json", "--geometry-only"});
    CHECK(ok.code == 0);
  }
  const Run grid = phedra_cli({"check", presets + "/grid-3x3.json", "--json"});
  CHECK(grid.code == 0);
  CHECK(json::parse(grid.out)["shared_vertex_groups"] == 120);  // 10 profiles x 12 shared vertices
}

TEST_CASE("every checked numeric option: one rule for its message, exit 2, never a long number", "[cli][errors]") {
  // Values each option refuses (0 only where it must be positive); the option's
  // own rule in words, the value as typed (cut to 20 characters).
  const std::string preset = presets + "/default.json", out = (fs::temp_directory_path() / "phedra-numeric-x").string();
  struct Option {
    std::vector<std::string> command;
    std::string name, rule;
    bool zero_refused;
  };
  const std::vector<Option> options{
      {{"check", preset}, "--samples", "a whole number from 2 to 10000000", true},
      {{"check", preset}, "--thickness", "a positive number", true},
      {{"check", preset}, "--max-growth", "0 (no bound) or a number, 1 or more", false},
      {{"check", preset}, "--max-panel-ratio", "0 (no bound) or a number, 1 or more", false},
      {{"check", preset}, "--intersection-samples", "a whole number from 1 to 1000000", true},
      {{"metrics", preset}, "--samples", "a whole number from 2 to 1000000", true},
      {{"intersections", preset}, "--samples", "a whole number from 1 to 1000000", true},
      {{"sample", preset, "-o", out + ".json"}, "--count", "a whole number from 2 to 1000000", true},
      {{"generate", preset, "-o", out + ".glb"}, "--intersection-samples", "a whole number from 1 to 1000000", true},
      {{"outlines", preset, "-o", out + ".pdf", "--thickness-mm", "3"}, "--kerf", "a number, 0 or more", false},
      {{"outlines", preset, "-o", out + ".pdf"}, "--thickness-mm", "a positive number", true},
      {{"repair", preset, "-o", out + ".json"}, "--require", "a number in [0, 1]", false},
      {{"repair", preset, "-o", out + ".json"}, "--restarts", "a whole number from 0 to 1000", false},
      {{"repair", preset, "-o", out + ".json"}, "--max-seconds", "a positive number", true},
      {{"optimize", preset, "-o", out + ".json", "--target", "flexion_width>=1"}, "--max-seconds", "a positive number", true},
      {{"optimize", preset, "-o", out + ".json", "--target", "flexion_width>=1"}, "--tol", "a positive number", true},
      {{"bench"}, "--max-vertices", "a whole number from 1000 to 100000000", true},
      {{"mechanics", preset}, "--bar", "a positive number", true},
      {{"mechanics", preset}, "--fold", "a positive number", true},
      {{"mechanics", preset}, "--bend", "a positive number", true},
      {{"mechanics", preset, "--material", "1000,0.3"}, "--thickness", "a positive number", true},
      {{"mechanics", preset, "--material", "1000,0.3", "--thickness", "0.05"}, "--length-scale", "a positive number", true},
  };
  const std::regex long_number("[0-9]{21,}");
  for (const Option& o : options) {
    std::vector<std::string> values{"-1", "nan", "-inf", "1e400", "abc", "123456789012345678901234567890"};
    if (o.zero_refused) values.push_back("0");
    if (o.rule.find("[0, 1]") != std::string::npos) values.push_back("1.5");
    if (o.rule.find("1 or more") != std::string::npos) values.push_back("0.5");
    for (const std::string& value : values) {
      if (value == "123456789012345678901234567890" && o.rule.find("or more") != std::string::npos) continue;  // a valid bound
      if (value == "123456789012345678901234567890" && o.rule.find("positive") != std::string::npos) continue;
      std::vector<std::string> args = o.command;
      args.push_back(o.name);
      args.push_back(value);
      const test::Run r = test::phedra_cli(args);
      CAPTURE(args, r.err);
      CHECK(r.code == 2);
      const std::string shown = value.size() <= 20 ? value : value.substr(0, 17) + "...";
      CHECK_THAT(r.err, Contains(o.name + ": must be " + o.rule + " (got " + shown + ")"));
      CHECK_FALSE(std::regex_search(r.err, long_number));
    }
  }
  CHECK_FALSE(fs::exists(out + ".json"));
  CHECK_FALSE(fs::exists(out + ".pdf"));
}

TEST_CASE("every numeric option of every command at 0, -1, nan, 1e-300 and 1e300: exit 0, 1 or 2, never 4",
          "[cli][errors]") {
  // The options are read from each command's --help (every FLOAT, INT or UINT
  // option, so a new one is swept too), each given with what it needs; `view`
  // serves until interrupted and is left out. No value a user can type is an
  // internal error, and no message holds a number longer than 20 characters.
  const std::string preset = presets + "/default.json";
  const std::string out = (fs::temp_directory_path() / "phedra-every-option").string();
  const std::map<std::string, std::vector<std::string>> commands{
      {"info", {"info", preset}},
      {"sample", {"sample", preset, "-o", out + ".json"}},
      {"check", {"check", preset}},
      {"repair", {"repair", preset, "-o", out + ".json"}},
      {"optimize", {"optimize", preset, "-o", out + ".json", "--target", "flexion_width>=0.01"}},
      {"intersections", {"intersections", preset}},
      {"metrics", {"metrics", preset}},
      {"mechanics", {"mechanics", preset}},
      {"outlines", {"outlines", preset, "-o", out + ".svg"}},
      {"develop", {"develop", presets + "/developed/flat-pattern.json", "-o", out + "-crease.svg"}},
      {"generate", {"generate", preset, "-o", out + ".glb"}},
      {"bench", {"bench", "--only", "evaluate", "--quick"}},
  };
  // What an option needs beside the command's base (otherwise refused for that, not for its value).
  auto needs = [](const std::string& command, const std::string& option) -> std::vector<std::string> {
    if (command == "mechanics" && (option == "--thickness" || option == "--length-scale")) {
      return option == "--thickness" ? std::vector<std::string>{"--material", "1000,0.3"}
                                     : std::vector<std::string>{"--material", "1000,0.3", "--thickness", "0.05"};
    }
    if (command == "mechanics" && option == "--samples") return {"--energy"};
    if (command == "outlines" && option == "--kerf") return {"--thickness-mm", "3"};
    if ((option == "--scale" || option == "--model-size") && command != "outlines" && command != "develop") {
      return {"--thickness-mm", "3"};
    }
    if (option == "--hinge-gap") return {"--thickness", "0.01"};
    return {};
  };
  const std::regex numeric(R"(^\s+(?:-\w,)?(--[\w-]+) (?:FLOAT|INT|UINT)\b)");
  const std::regex long_number("[0-9]{21,}");
  std::size_t swept = 0;
  for (const auto& [command, base] : commands) {
    const test::Run help = test::phedra_cli({command, "--help"});
    REQUIRE(help.code == 0);
    std::istringstream lines(help.out);
    for (std::string line; std::getline(lines, line);) {
      std::smatch m;
      if (!std::regex_search(line, m, numeric)) continue;
      const std::string option = m[1];
      if (command == "mechanics" && option == "--material") continue;  // E,NU: two numbers, its own test
      ++swept;
#ifdef PHEDRA_SANITIZE_BUILD
      // The largest (what overflows: a cast of 3e299 to long was found here); the
      // Release run gives every option all five.
      const std::vector<std::string> values{"1e300"};
#else
      const std::vector<std::string> values{"0", "-1", "nan", "1e-300", "1e300"};
#endif
      for (const std::string& value : values) {
        std::vector<std::string> args = base;
        for (const std::string& a : needs(command, option)) args.push_back(a);
        args.push_back(option);
        args.push_back(value);
        const test::Run r = test::phedra_cli(args);
        CAPTURE(args, r.code, r.err);
        CHECK((r.code == 0 || r.code == 1 || r.code == 2));
        CHECK_FALSE(std::regex_search(r.err, long_number));
        CHECK_FALSE(std::regex_search(r.out, long_number));
      }
    }
  }
  CHECK(swept >= 50);
  // Values past any use that the sweep's five do not reach.
  const test::Run kerf = test::phedra_cli({"outlines", preset, "-o", out + ".svg", "--thickness-mm", "3", "--kerf", "1e9"});
  CHECK(kerf.code == 2);
  CHECK_THAT(kerf.err, Contains("fits the page in no direction: a larger --page, a smaller --scale or --model-size, or "
                                "a smaller --kerf"));
  const test::Run thin = test::phedra_cli({"check", preset, "--thickness-mm", "1e-9"});
  CHECK(thin.code == 2);
  CHECK_THAT(thin.err, Contains("--thickness-mm: plates 1e-09 mm thick are below what the model resolves"));
  for (const char* extension : {".json", ".svg", "-crease.svg", ".glb"}) fs::remove(out + extension);
}
